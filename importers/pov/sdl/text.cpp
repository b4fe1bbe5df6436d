// text { ttf "Font.ttf" "String" Thickness, <Offset> } (POV-Ray 3.7 reference, "Text"): a union
// of one extruded glyph outline each (importers/pov/sdl/text_glyphs.h), in the xy plane from
// z = 0 to z = Thickness. The font is found as #include finds files (path_rules.h).
#include "importers/pov/sdl/parser.h"
#include "importers/pov/sdl/text_glyphs.h"

namespace fb::pov::sdl {

namespace {

// Debian's povray-includes links the fonts of /usr/share/povray-3.7/include to its font folder:
// links from a library folder may lead there (and nowhere else outside the allowed folders).
const std::vector<std::filesystem::path> kDebianPovRayFonts = {"/usr/share/fonts/truetype/povray"};

}  // namespace

bool Parser::parse_text(Object& o) {
  const Tok kind = next();
  if (kind.word("internal")) {
    warn_at(o.where, "text with an internal font: POV-Ray's built-in fonts are not here");
    return false;
  }
  if (!kind.word("ttf")) fail_at(location_of(kind), "expected ttf \"font file\" in text");
  const Value font = parse_expression();
  if (font.kind != ValueKind::kString) fail("text expects a font file name string after ttf");
  const SourceLocation font_at = here();
  accept(",");
  // As POV-Ray, a name without an extension is also tried with ".ttf" ("cyrvetic").
  std::optional<std::filesystem::path> path =
      resolve_include(font.text, nullptr, false, kDebianPovRayFonts);
  if (!path && std::filesystem::path(font.text).extension().empty())
    path = resolve_include(font.text + ".ttf", nullptr, false, kDebianPovRayFonts);
  if (!path) {  // POV-Ray stops there; the rest of the scene can still be drawn
    warn_at(font_at, "font \"" + font.text +
                         "\" is not in the scene's folder or the library paths: text left out");
    return false;
  }
  const Value string = parse_expression();
  if (string.kind != ValueKind::kString) fail("text expects the string to draw after the font");
  accept(",");
  const double thickness = parse_float();
  accept(",");
  const Value offset = parse_numeric(3);
  std::vector<PlacedGlyph> glyphs;
  try {
    glyphs = text_glyphs(*path, string.text, {offset.v[0], offset.v[1], offset.v[2]});
  } catch (const std::runtime_error& e) {
    fail_at(font_at, "font \"" + font.text + "\": " + e.what());
  }
  count_objects(glyphs.size());
  // A glyph is a prism (its outline swept in POV-Ray's y) turned so that the sweep runs along z:
  // canonical (x, y, z) -> (x, z, y), then moved to its place in the string.
  const Matrix turn = Matrix::from_rows({1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1});
  o.shape = Shape::kUnion;
  for (const PlacedGlyph& g : glyphs) {
    Object glyph;
    glyph.shape = Shape::kPrism;
    glyph.keyword = o.keyword;
    glyph.where = o.where;
    glyph.outline = g.outline;
    glyph.r0 = 0, glyph.r1 = thickness;
    glyph.world_from_object = Matrix::translate(g.position) * turn;
    o.children.push_back(std::move(glyph));
  }
  return true;
}

}  // namespace fb::pov::sdl
