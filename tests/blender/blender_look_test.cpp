// Blender's view transform for 8-bit outputs (core/image/display_transform.h) against Blender
// itself: look_transform.py has Blender save a synthetic float image (seven decades of log ramps in
// grey, primaries, secondaries and saturated mixes) as it saves a render, to PNG through its Color
// Management, and to EXR; filmback's DisplayTransform applied to that EXR must give Blender's PNG.
//
// Differences are in 8-bit levels (1/255) over every channel of every pixel. The bar is a
// mean of at most 1 level; the same OpenColorIO library, processor and float operations, and
// Blender's own rounding and dither reproduced, should make them identical (measured: 0 levels,
// docs/conventions.md "Images"), so at most one level anywhere is allowed: a value within a float
// rounding of a level's boundary is the only way they may differ.
//
// The plain sRGB curve (filmback's fallback when no config is found) is measured against
// Blender's Standard view too: the Standard view is a 1-D LUT of that curve.
//
// Then a whole shot (look_shot.py): radiometry_shot.py's diffuse-only sun_world shot with Filmic,
// the Medium High Contrast look, exposure 0.5 and Blender's default dither, exported with the
// add-on and rendered by Cycles and by filmback at 256 samples. The PNGs are compared where the
// linear images agree: every channel within kAgreement of Cycles' (measured against kDarkFraction
// of the image's mean where Cycles' is darker), which leaves out pixels where the two renders'
// noise differs by more; there Filmic's steepest slope turns 2 % into about 0.6 levels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "core/image/display_transform.h"
#include "core/image/image_io.h"
#include "tests/blender/blender_shot.h"
#include "tests/support/commands.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxMeanLevels = 1.0;
constexpr int kMaxLevels = 1;

struct Case {
  const char* name;
  const char* view;
  const char* look;
  double exposure_stops, gamma, dither;
};

// For gtest's test names and messages.
void PrintTo(const Case& c, std::ostream* out) {
  *out << c.name;
}

struct Levels {
  double mean = 0;
  int max = 0;
  size_t differing = 0, values = 0;
};

Levels compare(const std::vector<uint8_t>& filmback, const Image& blender) {
  Levels l;
  for (size_t i = 0; i < size_t(blender.width) * blender.height; ++i)
    for (size_t c = 0; c < 3; ++c) {
      const int b = int(std::lround(blender.pixels[i * blender.channels.size() + c] * 255.f));
      const int d = std::abs(int(filmback[i * 3 + c]) - b);
      l.mean += d, l.max = std::max(l.max, d), l.differing += d > 0, ++l.values;
    }
  l.mean /= double(l.values);
  return l;
}

// Blender's PNG and EXR for `c`, in work/look_<name>/.
std::pair<Image, Image> blender_images(const fs::path& blender, const Case& c) {
  const fs::path work = fs::path(FILMBACK_BLENDER_WORK_DIR) / (std::string("look_") + c.name);
  fs::remove_all(work);
  fs::create_directories(work);
  run_logged(quoted(blender) + " -b --factory-startup --python-exit-code 1 --python " +
                 quoted(FILMBACK_LOOK_TRANSFORM_PY) + " -- " + quoted(work) + " " + quoted(c.view) +
                 " " + quoted(c.look) + " " + std::to_string(c.exposure_stops) + " " +
                 std::to_string(c.gamma) + " " + std::to_string(c.dither),
             work / "blender.log");
  return {read_image(work / "blender.png"), read_image(work / "linear.exr")};
}

class BlenderLook : public WithBlender<testing::TestWithParam<Case>> {};

TEST_P(BlenderLook, FilmbackTransformGivesBlendersPng) {
  const Case& c = GetParam();
  const auto [png, linear] = blender_images(blender, c);
  ASSERT_EQ(png.width, linear.width);
  ASSERT_EQ(png.height, linear.height);
  ViewSettings settings;
  settings.view_transform = c.view;
  settings.look = c.look;
  settings.exposure_stops = c.exposure_stops;
  settings.gamma = c.gamma;
  settings.dither_intensity = c.dither;
  Diagnostics diagnostics;
  const DisplayTransform transform =
      DisplayTransform::create(settings, ViewSettingsOrigin{}, "", diagnostics);
  ASSERT_EQ(diagnostics.count(), 0u) << diagnostics.messages().front();
  const Levels l = compare(transform.encode(linear), png);
  std::printf("%s: %s: mean %.4f levels, max %d, %zu of %zu values differ\n", c.name,
              transform.description().c_str(), l.mean, l.max, l.differing, l.values);
  EXPECT_LE(l.mean, kMaxMeanLevels);
  EXPECT_LE(l.max, kMaxLevels);
  if (std::string(c.view) == "Standard" && std::string(c.look) == "None") {
    settings.view_transform.clear();  // the plain sRGB curve, as without a config
    const Levels curve =
        compare(DisplayTransform::create(settings, {}, "", diagnostics).encode(linear), png);
    std::printf(
        "%s: the plain sRGB curve against Blender's Standard view: mean %.4f levels, "
        "max %d, %zu of %zu values differ\n",
        c.name, curve.mean, curve.max, curve.differing, curve.values);
    EXPECT_LE(curve.mean, kMaxMeanLevels);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Views, BlenderLook,
    testing::Values(Case{"filmic_medium_high_contrast", "Filmic", "Medium High Contrast", 0.7, 1.2,
                         1.0},
                    Case{"filmic_none", "Filmic", "None", -1.3, 0.8, 0.5},
                    Case{"standard", "Standard", "None", 0.0, 1.0, 1.0},
                    Case{"standard_no_dither", "Standard", "None", 0.0, 1.0, 0.0},
                    Case{"standard_high_contrast", "Standard", "High Contrast", 1.5, 1.0, 2.0}),
    [](const testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

constexpr double kAgreement = 0.02;
constexpr double kDarkFraction = 0.02;
constexpr double kMinAgreeingFraction = 0.1;  // of the pixels: else the comparison says little

using BlenderLookShot = WithBlender<>;

TEST_F(BlenderLookShot, FilmbacksPngIsBlendersWhereTheLinearImagesAgree) {
  const fs::path work = fs::path(FILMBACK_BLENDER_WORK_DIR) / "look_shot";
  const ShotRenders r =
      render_shot(blender, "sun_world", work, FILMBACK_LOOK_SHOT_PY, {"filmback.png"});
  EXPECT_EQ(r.filmback_log.find("warning"), std::string::npos) << r.filmback_log;
  const Image cycles_png = read_image(work / "cycles.png");
  const Image filmback_png = read_image(work / "filmback.png");
  ASSERT_EQ(filmback_png.width, cycles_png.width);
  ASSERT_EQ(filmback_png.height, cycles_png.height);
  ASSERT_EQ(r.cycles.width, cycles_png.width);
  ASSERT_EQ(r.filmback.width, cycles_png.width);
  double mean_linear = 0;
  for (size_t i = 0; i < size_t(r.cycles.width) * r.cycles.height; ++i)
    for (size_t c = 0; c < 3; ++c)
      mean_linear += r.cycles.pixels[i * r.cycles.channels.size() + c];
  const double dark = kDarkFraction * mean_linear / (3.0 * r.cycles.width * r.cycles.height);
  const auto png_level = [](const Image& png, size_t i, size_t c) {
    return int(std::lround(png.pixels[i * png.channels.size() + c] * 255.f));
  };
  double agreeing_sum = 0, all_sum = 0;
  int agreeing_max = 0;
  size_t agreeing = 0;
  const size_t pixels = size_t(cycles_png.width) * cycles_png.height;
  for (size_t i = 0; i < pixels; ++i) {
    bool agree = true;
    int difference = 0;
    for (size_t c = 0; c < 3; ++c) {
      const double f = r.filmback.pixels[i * r.filmback.channels.size() + c];
      const double b = r.cycles.pixels[i * r.cycles.channels.size() + c];
      agree &= std::abs(f - b) <= kAgreement * std::max(b, dark);
      difference += std::abs(png_level(filmback_png, i, c) - png_level(cycles_png, i, c));
    }
    all_sum += difference;
    if (agree) {
      agreeing_sum += difference, ++agreeing;
      for (size_t c = 0; c < 3; ++c)
        agreeing_max = std::max(
            agreeing_max, std::abs(png_level(filmback_png, i, c) - png_level(cycles_png, i, c)));
    }
  }
  const double agreeing_mean = agreeing ? agreeing_sum / (3.0 * agreeing) : 0;
  std::printf(
      "look shot: %zu of %zu pixels agree within %.0f %% (linear); there the PNGs differ by %.3f "
      "levels on average, %d at most; over all pixels by %.3f; Blender %.1f s, filmback %.1f s\n",
      agreeing, pixels, 100 * kAgreement, agreeing_mean, agreeing_max, all_sum / (3.0 * pixels),
      r.blender_s, r.filmback_s);
  ASSERT_GE(double(agreeing), kMinAgreeingFraction * double(pixels));
  EXPECT_LE(agreeing_mean, kMaxMeanLevels);
}

}  // namespace
}  // namespace fb::test
