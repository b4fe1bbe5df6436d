#include "core/render/environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/accel/render_geometry.h"
#include "core/math/constants.h"
#include "core/render/light_sampler.h"

namespace fb {
namespace {

// A 16x8 sky of 0.5 with one texel of 40 at column 12, row 2 (from the top).
EnvironmentMap hot_spot_map() {
  EnvironmentMap map{"test", 16, 8, std::vector<Rgb>(16 * 8, Rgb(0.5f, 0.5f, 0.5f))};
  map.texels[2 * 16 + 12] = Rgb(40.f, 40.f, 40.f);
  return map;
}

// glTF direction of Blender's spherical angles: theta from Blender's +Z (glTF +Y), phi from
// Blender's +X towards +Y (glTF -Z).
Vec3f blender_direction(float theta, float phi) {
  return {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
}

TEST(EnvironmentLight, FollowsCyclesEquirectangularMapping) {
  EnvironmentMap map{"test", 4, 2, std::vector<Rgb>(8)};
  for (uint32_t i = 0; i < 8; ++i)
    map.texels[i] = Rgb(float(i), 0.f, 0.f);
  const EnvironmentLight light(map);
  // Cycles: u = 0.5 - phi / (2 pi), v = acos(z) / pi from the top. Texel centres sit at
  // u = (column + 0.5) / 4 and v = (row + 0.5) / 2, where bilinear lookup returns them exactly.
  for (uint32_t row = 0; row < 2; ++row)
    for (uint32_t column = 0; column < 4; ++column) {
      const float u = (column + 0.5f) / 4, v = (row + 0.5f) / 2;
      const Vec3f w = blender_direction(v * kPiF, (0.5f - u) * 2 * kPiF);
      EXPECT_NEAR(light.radiance(w).x, float(row * 4 + column), 1e-4f)
          << "row " << row << " column " << column;
    }
}

TEST(EnvironmentLight, SampledPdfIsThePdfOfTheDirectionAndIntegratesToOne) {
  const EnvironmentLight light(hot_spot_map());
  constexpr int kGrid = 64;
  int hot = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      Vec3f w;
      float pdf;
      ASSERT_TRUE(light.sample({(i + 0.5f) / kGrid, (j + 0.5f) / kGrid}, w, pdf));
      EXPECT_NEAR(light.pdf(w), pdf, 1e-3f * pdf);
      EXPECT_NEAR(length(w), 1.f, 1e-5f);
      hot += light.radiance(w).x > 10.f;
    }
  EXPECT_GT(hot, kGrid * kGrid / 4) << "the bright texel is importance-sampled";
  // Over the sphere, by a midpoint rule in (cos theta, phi): equal solid angles.
  double integral = 0;
  constexpr int kCells = 512;
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const float z = 1 - 2 * (i + 0.5f) / kCells, phi = 2 * kPiF * (j + 0.5f) / kCells;
      const float s = std::sqrt(1 - z * z);
      integral += light.pdf({s * std::cos(phi), z, s * std::sin(phi)});
    }
  EXPECT_NEAR(integral * 4 * kPiF / (double(kCells) * kCells), 1.0, 5e-3);
}

// Through the light sampler, a uniform world image of radiance L gives a surface the irradiance
// pi L (is_delta 0: combined with BSDF sampling by MIS); background() returns the same pdf.
TEST(EnvironmentLight, UniformImageGivesPiLThroughTheLightSampler) {
  Scene scene;
  scene.environment =
      EnvironmentMap{"uniform", 64, 32, std::vector<Rgb>(64 * 32, Rgb(2.f, 2.f, 2.f))};
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  // Rows are where the estimate varies (the image is uniform along them): a fine grid over them.
  constexpr int kColumns = 16, kRows = 4096;
  double sum = 0;
  for (int i = 0; i < kColumns; ++i)
    for (int j = 0; j < kRows; ++j) {
      const float u[3] = {0.5f, (i + 0.5f) / kColumns, (j + 0.5f) / kRows};
      fb_light_sample s;
      ASSERT_TRUE(sampler.sample({0, 0, 0}, u, s));
      EXPECT_EQ(s.is_delta, 0u);
      float pdf;
      EXPECT_FLOAT_EQ(sampler.background(Vec3f(s.direction), pdf).x, 2.f);
      EXPECT_NEAR(pdf, s.pdf, 1e-3f * s.pdf);
      if (s.direction[1] > 0.f) sum += double(s.radiance[0]) * s.direction[1] / s.pdf;
    }
  EXPECT_NEAR(sum / (kColumns * kRows), 2 * kPiF, 1e-3 * 2 * kPiF);
  // The command line's --background replaces the image.
  const LightSampler overridden(scene, Transform(), geometry, 0.0, Rgb(0.25f, 0.25f, 0.25f));
  float pdf = 1.f;
  EXPECT_FLOAT_EQ(overridden.background({0, 1, 0}, pdf).x, 0.25f);
  EXPECT_EQ(pdf, 0.f);
}

}  // namespace
}  // namespace fb
