// 8-bit outputs (core/image/display_transform.h, byte_quantize.h): Blender's rounding and dither by
// their definitions, the plain sRGB curve with exposure and gamma against closed forms, and how
// config and name problems are reported. Against Blender's own PNGs:
// tests/blender/blender_look_test.cpp.
#include "core/image/display_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

#include "core/image/byte_quantize.h"
#include "core/image/ocio_config_search.h"
#include "core/util/error.h"
#include "support/gltf_builder.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// IEC 61966-2-1.
double srgb(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

int level(double v) {
  return int(std::floor(std::clamp(v, 0.0, 1.0) * 255 + 0.5));
}

// Sets an environment variable for the scope, restoring the old value (or its absence) after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? setenv(name, value, 1) : unsetenv(name);
  }
  ~ScopedEnv() { old_ ? setenv(name_, old_->c_str(), 1) : unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

bool blender_config_installed() {
  std::vector<fs::path> searched;
  const ScopedEnv no_ocio("OCIO", nullptr);
  return choose_ocio_config({}, searched).has_value();
}

TEST(ByteQuantize, RoundsAsBlender) {
  EXPECT_EQ(unit_float_to_byte(-1.f), 0);
  EXPECT_EQ(unit_float_to_byte(0.f), 0);
  EXPECT_EQ(unit_float_to_byte(0.499f / 255), 0);
  EXPECT_EQ(unit_float_to_byte(0.5f / 255), 1);
  EXPECT_EQ(unit_float_to_byte(127.5f / 255), 128);
  EXPECT_EQ(unit_float_to_byte(1.f - 0.5f / 255), 255);
  EXPECT_EQ(unit_float_to_byte(7.f), 255);
  EXPECT_EQ(unit_float_to_byte(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(ByteQuantize, DitherIsBlendersTriangleNoisePerTaskOf64Rows) {
  constexpr uint32_t kWidth = 256, kHeight = 150;  // tasks of 64, 64 and 22 rows
  double sum = 0, lo = 1, hi = -1;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const double d = blender_dither_offset(x, y, kWidth, kHeight, 2.f) / (0.0033 * 2);
      sum += d, lo = std::min(lo, d), hi = std::max(hi, d);
    }
  // The sum of two uniform hashes minus 0.5: within [-0.5, 1.5), mean 0.5.
  EXPECT_GE(lo, -0.5);
  EXPECT_LT(hi, 1.5);
  EXPECT_NEAR(sum / (kWidth * kHeight), 0.5, 0.01);
  EXPECT_LT(lo, -0.4);
  EXPECT_GT(hi, 1.4);
  // Each task hashes the row within it: the first rows of the first two tasks are the same, the
  // short last task's rows are spread over t in [0, 1) as the full tasks' are.
  for (uint32_t x = 0; x < kWidth; x += 17) {
    EXPECT_EQ(blender_dither_offset(x, 0, kWidth, kHeight, 1.f),
              blender_dither_offset(x, 64, kWidth, kHeight, 1.f));
    EXPECT_EQ(blender_dither_offset(x, 128 + 11, kWidth, kHeight, 1.f),
              blender_dither_offset(x, 32, kWidth, 128, 1.f));  // t = 11/22 = 32/64
  }
  EXPECT_EQ(blender_dither_offset(3, 4, kWidth, kHeight, 0.f), 0.f);
}

TEST(DisplayTransformCurve, AppliesExposureCurveAndGammaInThatOrder) {
  const Image image{
      4,
      1,
      {"R", "G", "B"},
      {0.18f, 0.5f, 2.f, 0.0031308f, 0.f, -1.f, 0.05f, 0.05f, 0.05f, 0.7f, 0.1f, 0.3f}};
  const std::vector<uint8_t> plain = DisplayTransform().encode(image);
  const double values[12] = {0.18, 0.5, 2, 0.0031308, 0, -1, 0.05, 0.05, 0.05, 0.7, 0.1, 0.3};
  for (size_t i = 0; i < 12; ++i)
    EXPECT_EQ(plain[i], level(srgb(std::max(values[i], 0.0)))) << i;

  ViewSettings s;
  s.exposure_stops = 1.5;
  s.gamma = 2.2;
  Diagnostics d;
  const std::vector<uint8_t> graded = DisplayTransform::create(s, {}, {}, d).encode(image);
  EXPECT_EQ(d.count(), 0u);
  for (size_t i = 0; i < 12; ++i) {
    const double display = srgb(std::clamp(values[i] * std::pow(2.0, 1.5), 0.0, 1.0));
    EXPECT_EQ(graded[i], level(std::pow(display, 1 / 2.2))) << i;
  }
}

TEST(DisplayTransformCurve, TopRowIsTheImagesTopRowAndMissingChannelsAreZero) {
  const Image image{1, 2, {"Y"}, {1.f, 0.f}};
  const std::vector<uint8_t> bytes = DisplayTransform().encode(image);
  EXPECT_EQ(bytes, (std::vector<uint8_t>{255, 0, 0, 0, 0, 0}));
}

TEST(DisplayTransformConfig, WithoutAConfigAViewFallsBackToTheCurveWithAWarning) {
  const ScopedEnv no_ocio("OCIO", nullptr);
  const ScopedEnv nowhere("BLENDER_SYSTEM_DATAFILES", "/nonexistent/datafiles");
  ViewSettings s;
  s.view_transform = "Filmic";
  s.exposure_stops = 1;
  Diagnostics d;
  const DisplayTransform t = DisplayTransform::create(s, {}, {}, d);
  ASSERT_EQ(d.count(), 1u);
  EXPECT_NE(d.messages()[0].find("no OpenColorIO config"), std::string::npos);
  EXPECT_NE(d.messages()[0].find("/nonexistent/datafiles/colormanagement/config.ocio"),
            std::string::npos);
  EXPECT_NE(d.messages()[0].find("'Filmic'"), std::string::npos);
  const Image grey{1, 1, {"R", "G", "B"}, {0.18f, 0.18f, 0.18f}};
  EXPECT_EQ(t.encode(grey)[0], level(srgb(0.36)));  // the exposure still applies
  EXPECT_NE(
      t.description().find("in place of view transform 'Filmic', look 'None': no OpenColorIO"),
      std::string::npos)
      << t.description();
}

TEST(DisplayTransformConfig, AConfigTheUserNamesMustLoad) {
  const fs::path bad = test::scratch_dir() / "bad.ocio";
  std::ofstream(bad) << "not: [an OpenColorIO config\n";
  ViewSettings s;
  s.view_transform = "Filmic";
  Diagnostics d;
  try {
    DisplayTransform::create(s, {}, bad, d);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string() + ": the OpenColorIO config (--ocio-config)"),
              std::string::npos)
        << e.what();
  }
  const ScopedEnv ocio("OCIO", (test::scratch_dir() / "missing.ocio").c_str());
  try {
    DisplayTransform::create(s, {}, {}, d);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.ocio: the OpenColorIO config ($OCIO)"),
              std::string::npos)
        << e.what();
  }
}

TEST(DisplayTransformConfig, UnknownNamesAreUsageErrorsWhenTypedAndWarningsFromTheFile) {
  const ScopedEnv no_ocio("OCIO", nullptr);
  if (!blender_config_installed())
    GTEST_SKIP() << "no Blender OpenColorIO config: install Debian's package `blender`";
  ViewSettings s;
  s.view_transform = "Filmc";
  s.look = "Punchy";
  Diagnostics d;
  ViewSettingsOrigin typed;
  typed.view_typed = true;
  try {
    DisplayTransform::create(s, typed, {}, d);
    FAIL() << "expected a UsageError";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--view-transform 'Filmc': expected a view of display "
                                         "'sRGB': 'Standard', 'Filmic'"),
              std::string::npos)
        << e.what();
  }
  // From the file: Blender's fallback, the display's default view and no look, with a warning each
  // naming the file and the JSON path.
  const ViewSettingsOrigin file{"shot.gltf", "scenes[0].extensions.FILMBACK_blender"};
  const DisplayTransform t = DisplayTransform::create(s, file, {}, d);
  ASSERT_EQ(d.count(), 2u);
  EXPECT_NE(d.messages()[0].find("shot.gltf: scenes[0].extensions.FILMBACK_blender.view_transform: "
                                 "'Filmc': expected a view"),
            std::string::npos)
      << d.messages()[0];
  EXPECT_NE(d.messages()[1].find("FILMBACK_blender.look: 'Punchy': expected a look: 'None'"),
            std::string::npos)
      << d.messages()[1];
  EXPECT_EQ(t.settings().view_transform, "Standard");
  EXPECT_EQ(t.settings().look, "None");
}

TEST(DisplayTransformConfig, BlendersStandardViewIsTheSrgbCurveWithinALevel) {
  const ScopedEnv no_ocio("OCIO", nullptr);
  if (!blender_config_installed())
    GTEST_SKIP() << "no Blender OpenColorIO config: install Debian's package `blender`";
  Image ramp{1024, 1, {"R", "G", "B"}, {}};
  for (uint32_t x = 0; x < ramp.width; ++x)
    for (int c = 0; c < 3; ++c)
      ramp.pixels.push_back(float(x) / (ramp.width - 1));
  ViewSettings s;
  s.view_transform = "Standard";
  Diagnostics d;
  const std::vector<uint8_t> standard = DisplayTransform::create(s, {}, {}, d).encode(ramp);
  const std::vector<uint8_t> curve = DisplayTransform().encode(ramp);
  EXPECT_EQ(d.count(), 0u);
  for (size_t i = 0; i < curve.size(); ++i)
    EXPECT_LE(std::abs(standard[i] - curve[i]), 1) << i;
}

}  // namespace
}  // namespace fb
