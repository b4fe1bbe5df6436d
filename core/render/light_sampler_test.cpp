#include "core/render/light_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

namespace fb {
namespace {

Light point_light(double watts_per_sr, Vec3d at) {
  Light light;
  light.intensity = Rgb(float(watts_per_sr), float(watts_per_sr), float(watts_per_sr));
  light.world_from_light = Transform::translate(at);
  return light;
}

// Every value u can take (multiples of 2^-24) chooses each light exactly as often as its pdf says
// (so the estimator is exact over the grid), however dim a light is beside the others and wherever
// it is in the list.
TEST(LightSampler, ChoiceFrequenciesEqualTheirProbabilitiesOnTheSampleGrid) {
  for (bool dim_first : {true, false}) {
    Scene scene;
    const Light bright = point_light(1e9, {0, 10, 0}), dim = point_light(1e-3, {0, 1, 0});
    scene.lights = dim_first ? std::vector{dim, bright} : std::vector{bright, dim};
    const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
    const LightSampler sampler(scene, Transform(), geometry, 0.0);
    std::map<float, std::pair<uint32_t, float>> chosen;  // by distance: times chosen, pdf
    constexpr uint32_t kGrid = 1u << 24;
    for (uint32_t k = 0; k < kGrid; ++k) {
      const float u[3] = {float(k) * 0x1p-24f, 0.5f, 0.5f};
      fb_light_sample s;
      ASSERT_TRUE(sampler.sample({0, 0, 0}, u, s));
      auto& [times, pdf] = chosen[s.distance];
      ++times;
      pdf = s.pdf;
    }
    ASSERT_EQ(chosen.size(), 2u) << "both lights must be reachable";
    for (const auto& [distance, entry] : chosen)
      EXPECT_EQ(double(entry.first), double(entry.second) * kGrid)
          << "light at " << distance << " m, "
          << (dim_first ? "dim light first" : "dim light last");
  }
}

TEST(LightSampler, LightsWithoutPowerAreNeverChosen) {
  Scene scene;
  scene.lights = {point_light(0, {0, 1, 0}), point_light(2, {0, 2, 0})};
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  for (float u0 : {0.f, 0.25f, 0.999f}) {
    const float u[3] = {u0, 0, 0};
    fb_light_sample s;
    ASSERT_TRUE(sampler.sample({0, 0, 0}, u, s));
    EXPECT_FLOAT_EQ(s.radiance[0], 2.f / 4.f);  // the 2 W/sr light at 2 m
    EXPECT_EQ(s.pdf, 1.f);
  }
}

// Irradiance on a surface at `position` facing `normal` from a scene with one punctual light,
// over a stratified grid of the point sample (u[1], u[2]).
double irradiance(const Light& light, Vec3f position, Vec3f normal) {
  Scene scene;
  scene.lights = {light};
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  constexpr int kGrid = 256;
  double sum = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const float u[3] = {0.5f, (i + 0.5f) / kGrid, (j + 0.5f) / kGrid};
      fb_light_sample s;
      if (!sampler.sample(position, u, s)) continue;
      EXPECT_EQ(s.is_delta, 1u);  // reached by light sampling only, size or not
      const float cosine = dot(normal, Vec3f(s.direction));
      if (cosine > 0.f) sum += double(s.radiance[0]) * cosine / s.pdf;
    }
  return sum / (kGrid * kGrid);
}

// Cycles' soft point light is a disk of radius r facing the shading point with radiance
// I / (pi r^2); facing it from distance d, the disk's form factor gives E = I / (d^2 + r^2).
TEST(LightSampler, SoftPointLightGivesItsDisksIrradiance) {
  for (double radius : {0.0, 0.2, 0.8}) {
    Light light = point_light(3, {0, 2, 0});
    light.radius_m = radius;
    const double expected = 3 / (1.5 * 1.5 + radius * radius);
    EXPECT_NEAR(irradiance(light, {0, 0.5f, 0}, {0, 1, 0}), expected, 1e-4 * expected)
        << "radius " << radius;
  }
}

// Cycles' spot (kernel/light/spot.h, spot_light_attenuation): intensity I cos(theta) inside the
// cone, times smoothstep(t) over the last blend * (1 - cos(half angle)) of cos(theta), 0 outside.
TEST(LightSampler, CyclesSpotFallsOffWithCosineAndSmoothstep) {
  Light light = point_light(5, {0, 0, 0});  // shines down -Z
  light.type = LightType::kSpot;
  light.spot_falloff = SpotFalloff::kCycles;
  light.spot_outer_angle_rad = 0.6;
  light.spot_blend = 0.4;
  const double cos_edge = std::cos(0.6), smooth = (1 - cos_edge) * 0.4;
  for (double theta : {0.0, 0.3, 0.5, 0.55, 0.59, 0.61}) {
    const Vec3f w(float(std::sin(theta)), 0.f, float(-std::cos(theta)));
    double expected = 0;
    if (std::cos(theta) > cos_edge) {
      const double t = std::min(1.0, (std::cos(theta) - cos_edge) / smooth);
      expected = 5 * std::cos(theta) * t * t * (3 - 2 * t) / 4;  // at 2 m
    }
    EXPECT_NEAR(irradiance(light, w * 2.f, -w), expected, 1e-5 + 1e-5 * expected)
        << "theta " << theta;
  }
}

// Cycles' sun of angle a: directions through a disk of radius t = tan(a/2) one unit away, each
// with the full irradiance S, so a surface facing it gets S (2 / t^2)(sqrt(1 + t^2) - 1), the mean
// cosine over the disk; and no direction strays outside the cone.
TEST(LightSampler, SunAngleSpreadsItsDirectionsOverACone) {
  Light sun = point_light(3, {0, 0, 0});
  sun.type = LightType::kDirectional;
  sun.angle_rad = 0.4;
  const double t = std::tan(0.2);
  const double expected = 3 * 2 / (t * t) * (std::sqrt(1 + t * t) - 1);
  EXPECT_NEAR(irradiance(sun, {5, 5, 5}, {0, 0, 1}), expected, 1e-5 * expected);
  Scene scene;
  scene.lights = {sun};
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  for (float u1 : {0.f, 0.5f, 0.999f})
    for (float u2 : {0.f, 0.25f, 0.999f}) {
      const float u[3] = {0.5f, u1, u2};
      fb_light_sample s;
      ASSERT_TRUE(sampler.sample({0, 0, 0}, u, s));
      EXPECT_GE(s.direction[2], float(std::cos(0.2)) - 1e-6f);
    }
}

}  // namespace
}  // namespace fb
