#include "core/render/light_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// Whether a scene holding only `light` lights `at`, and the sample it draws there (u mid-range).
bool sample_only(const Light& light, Vec3f at, fb_light_sample& sample) {
  Scene scene;
  scene.lights = {light};
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  const float u[3] = {0.5f, 0.5f, 0.5f};
  return sampler.sample(at, u, sample);
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

// POV-Ray's light model (docs/pov.md, "Appearance"): no inverse-square law, but
// 2 / (1 + (d / fade_distance)^fade_power) when fade_power > 0 (POV-Ray's Attenuate_Light).
TEST(LightSampler, PovRayLightsFadeOnlyAsFadeDistanceAndPowerSay) {
  struct Case {
    double fade_distance, fade_power, distance, expected;
  };
  for (const Case& c : {Case{0, 0, 3, 1}, Case{0, 0, 40, 1}, Case{2, 2, 4, 2.0 / (1 + 4)},
                        Case{2, 2, 2, 1}, Case{5, 1, 1, 2.0 / 1.2}, Case{0, 1, 4, 0.25}}) {
    Light light = point_light(3, {0, c.distance, 0});
    light.decay = LightDecay::kPovRay;
    light.fade_distance_m = c.fade_distance, light.fade_power = c.fade_power;
    fb_light_sample s;
    ASSERT_TRUE(sample_only(light, {0, 0, 0}, s));
    EXPECT_NEAR(s.radiance[1], 3 * c.expected, 1e-5) << c.fade_distance << " " << c.fade_power;
    EXPECT_NEAR(s.distance, c.distance, 1e-5);
  }
}

// POV-Ray's spotlight: full inside `radius`, nothing beyond `falloff`, 3t^2 - 2t^3 in cos(angle)
// between them, all times cos(angle)^tightness.
TEST(LightSampler, PovRaySpotlightFollowsRadiusFalloffAndTightness) {
  const double deg = std::numbers::pi / 180;
  for (double tightness : {0.0, 10.0})
    for (double angle_deg : {0.0, 20.0, 33.0, 37.5, 44.0, 50.0, 120.0}) {
      Light spot = point_light(1, {0, 0, 0});  // at the origin, shining down -z
      spot.type = LightType::kSpot;
      spot.spot_falloff = SpotFalloff::kPov;
      spot.decay = LightDecay::kPovRay;
      spot.spot_inner_angle_rad = 30 * deg, spot.spot_outer_angle_rad = 45 * deg;
      spot.spot_tightness = tightness;
      const double a = angle_deg * deg;
      const Vec3f at(Vec3d{std::sin(a) * 2, 0, -std::cos(a) * 2});
      const double c = std::cos(a), c_radius = std::cos(30 * deg), c_falloff = std::cos(45 * deg);
      double expected = c <= 0 ? 0 : std::pow(c, tightness);
      if (c < c_radius) {
        const double t = std::clamp((c - c_falloff) / (c_radius - c_falloff), 0.0, 1.0);
        expected *= t * t * (3 - 2 * t);
      }
      fb_light_sample s;
      const bool lit = sample_only(spot, at, s);
      EXPECT_EQ(lit, expected > 0) << angle_deg;
      if (lit) {
        EXPECT_NEAR(s.radiance[0], expected, 1e-5) << angle_deg << " " << tightness;
      }
    }
}

TEST(LightSampler, ShadowlessLightsAskForNoShadowRay) {
  for (LightType type : {LightType::kPoint, LightType::kDirectional}) {
    Light light = point_light(1, {0, 5, 0});
    light.type = type;
    light.casts_shadows = false;
    fb_light_sample s;
    ASSERT_TRUE(sample_only(light, {0, 0, 0}, s));
    EXPECT_EQ(s.distance, 0.f);
  }
}

// POV-Ray's area_light <2,0,0>, <0,0,2>, 3, 2: points at x in {-1, 0, 1}, z in {-1, 1} about the
// light, each chosen by its share of u; the estimate is the grid's mean.
TEST(LightSampler, AreaLightSamplesItsGridPointsEvenly) {
  Scene scene;
  Light light = point_light(6, {0, 4, 0});
  light.decay = LightDecay::kPovRay;
  light.area_axis1 = {2, 0, 0}, light.area_axis2 = {0, 0, 2};
  light.area_size1 = 3, light.area_size2 = 2;
  scene.lights = {light};
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  std::map<std::pair<int, int>, int> hits;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 20; ++j) {
      const float u[3] = {0.5f, (i + 0.5f) / 30, (j + 0.5f) / 20};
      fb_light_sample s;
      ASSERT_TRUE(sampler.sample({0, 0, 0}, u, s));
      const Vec3f q = Vec3f(s.direction) * s.distance;
      EXPECT_NEAR(q.y, 4, 1e-5);
      EXPECT_NEAR(s.radiance[0], 6, 1e-5);  // no fading: every point brings the full intensity
      ++hits[{int(std::lround(q.x)), int(std::lround(q.z))}];
      EXPECT_NEAR(q.x, std::lround(q.x), 1e-5);
    }
  ASSERT_EQ(hits.size(), 6u);
  for (const auto& [cell, count] : hits) {
    EXPECT_EQ(count, 100) << cell.first << " " << cell.second;
    EXPECT_LE(std::abs(cell.first), 1);
    EXPECT_EQ(std::abs(cell.second), 1);
  }
}

}  // namespace
}  // namespace fb
