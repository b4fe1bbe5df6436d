// pigment { image_map { [type] "file" [gamma G] modifiers } } (POV-Ray 3.7 reference, "Image
// Map"): the file found as #include finds files, its projection, repetition, interpolation,
// transparency and how its values decode to linear (docs/pov.md, "Image maps").
#include <algorithm>
#include <cctype>
#include <optional>
#include <string>
#include <string_view>

#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// The file types image_map reads through OpenImageIO, each with the extensions POV-Ray tries
// when the name has none. gif, iff, pot and sys are not read (reported).
struct ImageMapFileType {
  std::string_view keyword;
  std::string_view extensions[2];
};
constexpr ImageMapFileType kImageMapFileTypes[] = {
    {"png", {".png", ""}},       {"jpeg", {".jpg", ".jpeg"}}, {"tga", {".tga", ""}},
    {"tiff", {".tif", ".tiff"}}, {"exr", {".exr", ""}},       {"hdr", {".hdr", ""}},
    {"ppm", {".ppm", ""}},       {"pgm", {".pgm", ""}},       {"bmp", {".bmp", ""}}};
constexpr std::string_view kUnreadImageMapTypes[] = {"gif", "iff", "pot", "sys", "function"};

const ImageMapFileType* image_map_file_type(std::string_view keyword) {
  for (const ImageMapFileType& type : kImageMapFileTypes)
    if (type.keyword == keyword) return &type;
  return nullptr;
}

// Files of floating-point values hold linear light; POV-Ray 3.7 decodes every other file (with
// no gamma of its own) by the sRGB curve (checked on its render of an 8-bit PNG).
bool image_map_file_is_linear(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".exr" || ext == ".hdr";
}

}  // namespace

// After `image_map`: the block, into `p` (its pattern kImageMap, or averaged when the file type
// is one filmback does not read).
void Parser::parse_image_map(Pigment& p) {
  expect("{");
  const ImageMapFileType* type = nullptr;
  const Tok& first = peek();
  if (first.keyword() && std::find(std::begin(kUnreadImageMapTypes), std::end(kUnreadImageMapTypes),
                                   first.token.text) != std::end(kUnreadImageMapTypes)) {
    // rendered in the parser's estimate of its average (reported by the converter)
    p.pattern = Pattern::kSolid;
    p.averaged = true;
    p.name = "image_map " + first.token.text;
    skip_rest_of_block();
    return;
  }
  if (first.keyword() && (type = image_map_file_type(first.token.text))) next();
  const SourceLocation where = location_of(peek());
  const Value name = parse_expression();
  if (name.kind != ValueKind::kString) fail_at(where, "image_map expects an image file name");
  SolidImageMap& map = p.image_map;
  map = {};
  std::optional<double> file_gamma;  // `gamma G`; 0 for `gamma srgb`
  for (;;) {
    Tok tok = next();  // directives run
    if (tok.symbol("}")) break;
    if (tok.word("map_type")) {
      // POV-Ray projects any other map_type as planar (imageutil.cpp's map_pos)
      const int kind = int(parse_float());
      map.projection = kind == 1 || kind == 2 || kind == 5 ? SolidImageProjection(kind)
                                                           : SolidImageProjection::kPlanar;
    } else if (tok.word("once")) {
      map.once = true;
    } else if (tok.word("interpolate")) {
      // 2 bilinear, 3 bicubic, 4 normalised distance (read as bilinear: docs/pov.md)
      const int kind = int(parse_float());
      map.interpolation = kind == 3                ? TextureInterpolation::kCubic
                          : kind == 2 || kind == 4 ? TextureInterpolation::kLinear
                                                   : TextureInterpolation::kClosest;
    } else if (tok.word("filter") || tok.word("transmit")) {
      float& all = tok.word("filter") ? map.filter_all : map.transmit_all;
      if (peek().word("all")) {
        next();
        all = float(parse_float());
      } else {  // a palette entry's: not kept
        parse_float();
        accept(",");
        parse_float();
        unsupported("image_map " + tok.token.text + " of one palette entry", location_of(tok));
      }
    } else if (tok.word("gamma")) {
      if (peek().word("srgb")) {
        next();
        file_gamma = 0;
      } else {
        file_gamma = parse_float();
      }
    } else if (tok.word("premultiplied")) {
      parse_bool_option();
    } else if (tok.word("use_alpha") || tok.word("use_colour") || tok.word("use_color") ||
               tok.word("use_index")) {
      // how an image_pattern or bump_map reads the image; a colour image map uses its colours
    } else if (tok.word("major_radius")) {
      map.major_radius = parse_float();
    } else {
      fail_at(location_of(tok), "unexpected '" + tok.token.text + "' in image_map");
    }
  }
  // A name without extension gets its type's, or, with no type, each type's in turn (POV-Ray
  // 3.7 finds `image_map { "sign" }` as sign.jpg).
  std::optional<std::filesystem::path> file = resolve_include(name.text, nullptr, false);
  if (!file && std::filesystem::path(name.text).extension().empty())
    for (const ImageMapFileType& candidate : kImageMapFileTypes)
      for (std::string_view ext : candidate.extensions)
        if (!file && !ext.empty() && (!type || type == &candidate))
          file = resolve_include(name.text + std::string(ext), nullptr, false);
  if (!file)
    fail_at(where, "cannot find the image_map image \"" + name.text +
                       "\" in the scene's folder or a library path (paths leaving those "
                       "folders, through '..' or a symbolic link, are refused)");
  // How the texels decode to linear, as POV-Ray 3.7 decides when it reads the file: the gamma the
  // scene gives; else linear for float files; else, in a legacy scene (#version before 3.7, no
  // assumed_gamma), the values as they are, which the converter decodes as it decodes the
  // scene's colours (2.2, pov_appearance's colour_gamma); else the sRGB curve.
  if (file_gamma) {
    map.srgb = *file_gamma == 0;
    map.decode_gamma = float(*file_gamma);
  } else if (image_map_file_is_linear(*file)) {
    map.srgb = false;
  } else if (scene_.version < 3.7 && !scene_.assumed_gamma) {
    map.srgb = false;
    map.decode_gamma = 2.2f;
  }
  const auto known = std::find(scene_.images.begin(), scene_.images.end(), *file);
  map.image = uint32_t(known - scene_.images.begin());
  if (known == scene_.images.end()) scene_.images.push_back(*file);
  p.pattern = Pattern::kImageMap;
  p.averaged = false;
}

}  // namespace fb::pov::sdl
