#include "importers/pov/sdl/text_glyphs.h"

#include <algorithm>
#include <cstdint>
#include <map>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H
#include FT_TRUETYPE_TABLES_H
#include FT_TRUETYPE_TAGS_H

namespace fb::pov::sdl {

namespace {

// FreeType's library and one face, released however the reading ends.
class FontFace {
 public:
  explicit FontFace(const std::filesystem::path& font) {
    if (FT_Init_FreeType(&library_)) throw std::runtime_error("FreeType does not start");
    if (FT_New_Face(library_, font.c_str(), 0, &face_)) {
      FT_Done_FreeType(library_);
      throw std::runtime_error("not a font FreeType reads");
    }
  }
  ~FontFace() {
    FT_Done_Face(face_);
    FT_Done_FreeType(library_);
  }
  FontFace(const FontFace&) = delete;
  FontFace& operator=(const FontFace&) = delete;
  FT_Face face() const { return face_; }

 private:
  FT_Library library_ = nullptr;
  FT_Face face_ = nullptr;
};

// The horizontal metrics POV-Ray spaces glyphs by, straight from the font's `hmtx` table:
// advance width and left side bearing in font units.
class HorizontalMetrics {
 public:
  explicit HorizontalMetrics(FT_Face face) {
    const auto* hhea = static_cast<const TT_HoriHeader*>(FT_Get_Sfnt_Table(face, FT_SFNT_HHEA));
    FT_ULong length = 0;
    if (!hhea || FT_Load_Sfnt_Table(face, TTAG_hmtx, 0, nullptr, &length))
      throw std::runtime_error("no TrueType horizontal metrics (hhea, hmtx)");
    table_.resize(length);
    if (FT_Load_Sfnt_Table(face, TTAG_hmtx, 0, table_.data(), &length))
      throw std::runtime_error("cannot read the hmtx table");
    long_metrics_ = hhea->number_Of_HMetrics;
    if (long_metrics_ == 0 || 4 * size_t(long_metrics_) > table_.size())
      throw std::runtime_error("the hmtx table is shorter than hhea says");
  }
  int advance(FT_UInt glyph) const {
    return word(4 * size_t(std::min<FT_UInt>(glyph, long_metrics_ - 1)));
  }
  int left_side_bearing(FT_UInt glyph) const {
    const size_t at = glyph < long_metrics_
                          ? 4 * size_t(glyph) + 2
                          : 4 * size_t(long_metrics_) + 2 * (glyph - long_metrics_);
    return at + 2 <= table_.size() ? int16_t(word(at)) : 0;
  }

 private:
  int word(size_t at) const { return table_[at] << 8 | table_[at + 1]; }
  std::vector<FT_Byte> table_;
  FT_UInt long_metrics_ = 0;
};

// FT_Outline_Decompose's pen: each contour's segments, the last ending exactly at its start.
struct GlyphPen {
  Outline outline;
  double em = 1;  // font units per em
  Vec2d at, contour_start;
  size_t contour_first = 0;

  Vec2d point(const FT_Vector* v) const { return {v->x / em, v->y / em}; }
  void add(OutlineSegment s) {
    if (s.degree == 1 && s.start.x == s.end.x && s.start.y == s.end.y) return;
    outline.segments.push_back(s);
    at = s.end;
  }
  void close() {
    if (outline.segments.size() == contour_first) return;
    if (at.x != contour_start.x || at.y != contour_start.y) {
      OutlineSegment& last = outline.segments.back();
      const Vec2d gap = contour_start - last.end;
      if (std::hypot(gap.x, gap.y) < 1e-12)
        last.end = contour_start;  // rounding in the decomposition: shared bit for bit
      else
        add(line_segment(at, contour_start));
    }
  }
};

GlyphPen& pen_of(void* user) {
  return *static_cast<GlyphPen*>(user);
}

const FT_Outline_Funcs kGlyphPenFunctions = {
    [](const FT_Vector* to, void* user) {
      GlyphPen& pen = pen_of(user);
      pen.close();
      pen.at = pen.contour_start = pen.point(to);
      pen.contour_first = pen.outline.segments.size();
      return 0;
    },
    [](const FT_Vector* to, void* user) {
      GlyphPen& pen = pen_of(user);
      pen.add(line_segment(pen.at, pen.point(to)));
      return 0;
    },
    [](const FT_Vector* control, const FT_Vector* to, void* user) {
      GlyphPen& pen = pen_of(user);
      pen.add(quadratic_bezier_segment(pen.at, pen.point(control), pen.point(to)));
      return 0;
    },
    [](const FT_Vector* control1, const FT_Vector* control2, const FT_Vector* to, void* user) {
      GlyphPen& pen = pen_of(user);
      pen.add(
          cubic_bezier_segment(pen.at, pen.point(control1), pen.point(control2), pen.point(to)));
      return 0;
    },
    0,
    0};

// The glyph's outline in em units (null when it draws nothing, as a space) and the least x of
// its points in font units (the TrueType glyph header's xMin, which POV-Ray aligns by).
std::pair<std::shared_ptr<const Outline>, FT_Pos> load_glyph(FT_Face face, FT_UInt glyph) {
  if (FT_Load_Glyph(face, glyph, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP) ||
      face->glyph->format != FT_GLYPH_FORMAT_OUTLINE)
    throw std::runtime_error("glyph " + std::to_string(glyph) + " has no outline");
  FT_Outline& source = face->glyph->outline;
  FT_BBox box{};
  FT_Outline_Get_CBox(&source, &box);
  GlyphPen pen;
  pen.em = face->units_per_EM;
  if (FT_Outline_Decompose(&source, &kGlyphPenFunctions, &pen))
    throw std::runtime_error("glyph " + std::to_string(glyph) + "'s outline is malformed");
  pen.close();
  if (pen.outline.segments.empty()) return {nullptr, box.xMin};
  finish_outline(pen.outline);
  return {std::make_shared<const Outline>(std::move(pen.outline)), box.xMin};
}

}  // namespace

std::vector<PlacedGlyph> text_glyphs(const std::filesystem::path& font, const std::string& text,
                                     Vec3d offset) {
  if (text.size() > kMaxTextCharacters)
    throw std::runtime_error(std::to_string(text.size()) + " characters, more than the " +
                             std::to_string(kMaxTextCharacters) + " taken");
  const FontFace font_face(font);
  FT_Face face = font_face.face();
  if (!FT_IS_SFNT(face) || face->units_per_EM == 0) throw std::runtime_error("not a TrueType font");
  const HorizontalMetrics metrics(face);
  const double unit = 1.0 / face->units_per_EM;
  std::map<FT_UInt, std::pair<std::shared_ptr<const Outline>, FT_Pos>> loaded;
  std::vector<PlacedGlyph> glyphs;
  Vec3d pen{0, 0, 0};
  FT_UInt previous = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const FT_UInt glyph = FT_Get_Char_Index(face, static_cast<unsigned char>(text[i]));
    auto found = loaded.find(glyph);
    if (found == loaded.end()) found = loaded.emplace(glyph, load_glyph(face, glyph)).first;
    const auto& [outline, x_min] = found->second;
    const int lsb = metrics.left_side_bearing(glyph), advance = metrics.advance(glyph);
    Vec3d position{0, 0, 0};
    // POV-Ray 3.7 (TrueType::ProcessNewTTF): the first glyph's left edge at x = 0; the others at
    // the pen plus their side bearing past their left edge and the pair's kerning (at least
    // -1 em); the pen then moves by the advance (the first glyph's less its side bearing). Its
    // y follows the pen; its z stays 0 whatever the offset's z (as in POV-Ray).
    if (i == 0) {
      position.x = -double(x_min) * unit;
      pen.x = (advance - lsb) * unit;
    } else {
      FT_Vector kerning{0, 0};
      if (FT_HAS_KERNING(face))
        FT_Get_Kerning(face, previous, glyph, FT_KERNING_UNSCALED, &kerning);
      const double kern = std::max<double>(kerning.x, -double(face->units_per_EM));
      position.x = pen.x + (lsb - double(x_min) + kern) * unit;
      position.y = pen.y;
      pen.x += (advance + kern) * unit;
    }
    pen = pen + offset;
    previous = glyph;
    if (outline) glyphs.push_back({outline, position});
  }
  return glyphs;
}

}  // namespace fb::pov::sdl
