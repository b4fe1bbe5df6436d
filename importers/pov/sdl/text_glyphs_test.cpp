// The glyphs of POV-Ray's text from the fonts povray-includes ships, read with FreeType: closed
// outlines in em units, even-odd holes, the first glyph's left edge at x = 0, the offset added per
// character, and unreadable fonts refused. Where POV-Ray puts them is checked against its own
// renders (tests/pov/pov_geometry_render_test.cpp).
#include "importers/pov/sdl/text_glyphs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fb::pov::sdl {
namespace {

const std::filesystem::path kPovFonts = "/usr/share/povray-3.7/include";

class TextGlyphs : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kPovFonts / "timrom.ttf"))
      GTEST_SKIP() << "POV-Ray's fonts are not installed (Debian package povray-includes)";
  }
};

TEST_F(TextGlyphs, OutlinesAreClosedAndTheFirstGlyphStartsAtZero) {
  const auto glyphs = text_glyphs(kPovFonts / "timrom.ttf", "Ob", {0, 0, 0});
  ASSERT_EQ(glyphs.size(), 2u);
  EXPECT_EQ(glyphs[0].position.x + glyphs[0].outline->lo.x, 0);
  EXPECT_GT(glyphs[1].position.x, glyphs[0].position.x + glyphs[0].outline->hi.x * 0.5);
  for (const PlacedGlyph& g : glyphs) {
    // Closed: every segment's end is where a segment starts, bit for bit.
    for (const OutlineSegment& s : g.outline->segments) {
      bool continued = false;
      for (const OutlineSegment& t : g.outline->segments)
        continued = continued || (t.start.x == s.end.x && t.start.y == s.end.y);
      EXPECT_TRUE(continued);
    }
    // Em units: a letter is about half an em to an em tall, standing on the baseline.
    EXPECT_GT(g.outline->hi.y, 0.4);
    EXPECT_LT(g.outline->hi.y, 1.0);
    EXPECT_NEAR(g.outline->lo.y, 0, 0.05);
  }
  // The O's counter is a hole: its centre is outside, its ring inside.
  const Outline& o = *glyphs[0].outline;
  const Vec2d centre = (o.lo + o.hi) * 0.5;
  EXPECT_FALSE(outline_contains(o, centre));
  EXPECT_TRUE(outline_contains(o, {o.lo.x + 0.02, centre.y}));
}

TEST_F(TextGlyphs, OffsetIsAddedAfterEveryCharacterAndSpacesOnlyAdvance) {
  const auto plain = text_glyphs(kPovFonts / "cyrvetic.ttf", "H H", {0, 0, 0});
  const auto spread = text_glyphs(kPovFonts / "cyrvetic.ttf", "H H", {0.25, 0.1, 3});
  ASSERT_EQ(plain.size(), 2u);  // the space draws nothing
  ASSERT_EQ(spread.size(), 2u);
  EXPECT_NEAR(spread[1].position.x - plain[1].position.x, 2 * 0.25, 1e-12);
  EXPECT_NEAR(spread[1].position.y, 2 * 0.1, 1e-12);
  EXPECT_EQ(spread[1].position.z, 0);  // POV-Ray never moves a glyph in z
  EXPECT_GT(plain[1].position.x, plain[0].outline->hi.x + 0.1);
}

TEST_F(TextGlyphs, UnreadableFontsAndLongStringsAreRefused) {
  const auto not_a_font = std::filesystem::temp_directory_path() / "filmback_not_a_font.ttf";
  std::ofstream(not_a_font) << "text, not a font";
  EXPECT_THROW(text_glyphs(not_a_font, "A", {0, 0, 0}), std::runtime_error);
  std::filesystem::remove(not_a_font);
  EXPECT_THROW(
      text_glyphs(kPovFonts / "timrom.ttf", std::string(kMaxTextCharacters + 1, 'a'), {0, 0, 0}),
      std::runtime_error);
}

}  // namespace
}  // namespace fb::pov::sdl
