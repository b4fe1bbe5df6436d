#include "core/render/light_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include <filmback/geometry.h>
#include <filmback/sampling.h>

#include "tests/support/polygon_irradiance.h"

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
      const float cosine = dot(normal, Vec3f(s.direction));
      if (cosine > 0.f) sum += double(s.radiance[0]) * cosine / s.pdf;
    }
  return sum / (kGrid * kGrid);
}

// Cycles 3.4's soft point light is a disk of radius r facing the shading point with radiance
// I / (pi r^2); facing it from distance d, the disk's form factor gives E = I / (d^2 + r^2). Radius
// 0 stays a delta light.
TEST(LightSampler, SoftPointLightGivesItsDisksIrradiance) {
  for (double radius : {0.0, 0.2, 0.8}) {
    Light light = point_light(3, {0, 2, 0});
    light.radius_m = radius;
    const double expected = 3 / (1.5 * 1.5 + radius * radius);
    EXPECT_NEAR(irradiance(light, {0, 0.5f, 0}, {0, 1, 0}), expected, 1e-4 * expected)
        << "radius " << radius;
    fb_light_sample s;
    ASSERT_TRUE(sample_only(light, {0, 0.5f, 0}, s));
    EXPECT_EQ(s.is_delta, radius == 0 ? 1u : 0u);
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

// ---------------------------------------------------------------------------------------------
// Lights with a size (sized_lights.h): light sampling alone, BSDF-style sampling finding them
// through crossed() alone, and the two combined by the power heuristic estimate the same
// irradiance, the value in closed form or by quadrature. That the combination is unbiased also
// requires the pdf a crossing reports to be the density sample() draws the same point with; the
// last test checks that directly.

constexpr double kPiD = std::numbers::pi;

struct Estimates {
  double light = 0, bsdf = 0, mis = 0;
};

// Irradiance at p on a surface of normal n, from the scene's lights, three ways. Light sampling:
// 2^20 samples, the light choice u[0] stratified evenly (so each light is chosen in proportion to
// its pdf to within 2^-20) and the point (u[1], u[2]) from Roberts' R2 sequence (a Kronecker
// sequence of low discrepancy). BSDF-style: cosine-weighted directions about n (a Lambertian
// BSDF's sampling, pdf cos / pi) on a stratified 1024 x 1024 grid, each ray's crossings weighing
// L cos / pdf. MIS: both, each weighted by the power heuristic against the other's pdf.
Estimates estimate(const Scene& scene, Vec3f p, Vec3f n) {
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  constexpr int kLightSamples = 1 << 20, kDirections = 1024;
  constexpr double kPlastic = 1.32471795724474602596;  // R2's generator
  Estimates e;
  for (int k = 0; k < kLightSamples; ++k) {
    const double r1 = 0.5 + k / kPlastic, r2 = 0.5 + k / (kPlastic * kPlastic);
    const float u[3] = {(k + 0.5f) / kLightSamples, float(r1 - std::floor(r1)),
                        float(r2 - std::floor(r2))};
    fb_light_sample s;
    if (!sampler.sample(p, u, s) || !(s.pdf > 0.f)) continue;
    const float cosine = dot(n, Vec3f(s.direction));
    if (!(cosine > 0.f)) continue;
    const double f = double(s.radiance[0]) * cosine / s.pdf;
    e.light += f;
    e.mis += f * (s.is_delta ? 1.f : power_heuristic(s.pdf, cosine / float(kPiD)));
  }
  const double light_count = kLightSamples;
  e.light /= light_count;
  e.mis /= light_count;
  const Frame frame(n);
  double bsdf = 0, mis = 0;
  for (int i = 0; i < kDirections; ++i)
    for (int j = 0; j < kDirections; ++j) {
      const Vec3f local =
          sample_cosine_hemisphere({(i + 0.5f) / kDirections, (j + 0.5f) / kDirections});
      if (!(local.z > 0.f)) continue;
      const float pdf = local.z / float(kPiD);
      fb_ray ray{};
      p.store(ray.origin);
      frame.to_world(local).store(ray.direction);
      ray.t_max = HUGE_VALF;
      fb_light_crossing crossings[8];
      const uint32_t count = sampler.crossed(ray, HUGE_VALF, crossings, 8);
      for (uint32_t c = 0; c < count; ++c) {
        const double f = double(crossings[c].radiance[0]) * local.z / pdf;
        bsdf += f;
        mis += f * power_heuristic(pdf, crossings[c].pdf);
      }
    }
  const double direction_count = double(kDirections) * kDirections;
  e.bsdf = bsdf / direction_count;
  e.mis += mis / direction_count;
  return e;
}

// Deterministic point sets: light sampling and the MIS combination (whose light half carries most
// of the weight) converge fast; BSDF-style sampling meets the light's outline in a grid of 2^20
// directions, so it is held to a looser bound.
void expect_agree(const Estimates& e, double expected, const std::string& what) {
  EXPECT_NEAR(e.light, expected, 5e-4 * expected) << what << ": light sampling";
  EXPECT_NEAR(e.bsdf, expected, 2e-3 * expected) << what << ": BSDF sampling and crossed()";
  EXPECT_NEAR(e.mis, expected, 5e-4 * expected) << what << ": MIS of both";
}

// A light that takes half of light selection but lights nothing above the tested surface (it lies
// below it), so that the light under test is chosen with a probability below 1 and the pdfs must
// carry that choice.
Light distractor() {
  return point_light(5, {0, -3, 0});
}

Scene scene_of(const Light& light) {
  Scene scene;
  scene.lights = {light, distractor()};
  return scene;
}

const Vec3f kShadingPoint(0.f, 0.f, 0.f);
const Vec3f kTilted = normalize(Vec3f(0.25f, 1.f, 0.1f));

// An area light centred at `centre`, shining at `target`.
Light area_light(Vec3d centre, Vec3d target, AreaShape shape, double size_x, double size_y,
                 double radiance, double spread_rad = kPiD) {
  Light light;
  light.type = LightType::kArea;
  light.world_from_light = Transform::look_at(centre, target, {0, 0, 1});
  light.area_shape = shape;
  light.size_x_m = size_x, light.size_y_m = size_y;
  light.spread_rad = spread_rad;
  light.intensity = Rgb(float(radiance), float(radiance), float(radiance));
  return light;
}

// The corners of the light's rectangle, or of a 4096-gon inscribed in its ellipse (whose area
// falls short of the ellipse's by 4e-7).
std::vector<Vec3d> outline(const Light& light) {
  const Vec3d c = light.world_from_light.point({0, 0, 0});
  const Vec3d u = light.world_from_light.vector({light.size_x_m / 2, 0, 0});
  const Vec3d v = light.world_from_light.vector({0, light.size_y_m / 2, 0});
  if (light.area_shape == AreaShape::kRectangle)
    return {c - u - v, c + u - v, c + u + v, c - u + v};
  std::vector<Vec3d> corners;
  for (int i = 0; i < 4096; ++i) {
    const double a = 2 * kPiD * i / 4096;
    corners.push_back(c + u * std::cos(a) + v * std::sin(a));
  }
  return corners;
}

// Cycles 3.4's spread attenuation as scene/light.cpp and area_light_spread_attenuation write it
// (an independent transcription: spread_angle is the complement of half the spread).
double cycles_spread_attenuation(double cos_theta, double spread_rad) {
  const double spread_angle = 0.5 * (kPiD - std::max(spread_rad, kPiD / 180));
  const double tan_spread = std::tan(spread_angle);
  if (!(tan_spread > 1e-12)) return 1;  // 180 degrees: Cycles skips the attenuation
  const double normalize = 2 / (2 + (2 * spread_angle - kPiD) * tan_spread);
  const double tan_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta)) / cos_theta;
  return std::max((1 - tan_spread * tan_theta) * normalize, 0.0);
}

// E = integral over the light of L a(theta_light) cos_p cos_light / d^2 dA, by the midpoint rule
// on a 1000 x 1000 grid (polar for an ellipse, so its outline is exact).
double area_light_quadrature(const Light& light, Vec3d p, Vec3d n) {
  const Vec3d c = light.world_from_light.point({0, 0, 0});
  const Vec3d u = light.world_from_light.vector({light.size_x_m / 2, 0, 0});
  const Vec3d v = light.world_from_light.vector({0, light.size_y_m / 2, 0});
  const Vec3d normal = normalize(light.world_from_light.vector({0, 0, -1}));
  const bool ellipse = light.area_shape == AreaShape::kEllipse;
  constexpr int kSteps = 1000;
  double sum = 0;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const double a = (i + 0.5) / kSteps, b = (j + 0.5) / kSteps;
      Vec3d x;
      double jacobian;  // dA per unit of (a, b)
      if (ellipse) {
        x = c + (u * std::cos(2 * kPiD * b) + v * std::sin(2 * kPiD * b)) * a;
        jacobian = length(u) * length(v) * a * 2 * kPiD;
      } else {
        x = c + u * (2 * a - 1) + v * (2 * b - 1);
        jacobian = 4 * length(u) * length(v);
      }
      const Vec3d d = x - p;
      const double distance2 = dot(d, d), distance = std::sqrt(distance2);
      const double cos_p = dot(n, d) / distance, cos_light = -dot(normal, d) / distance;
      if (cos_p <= 0 || cos_light <= 0) continue;
      sum += cycles_spread_attenuation(cos_light, light.spread_rad) * cos_p * cos_light /
             distance2 * jacobian;
    }
  return double(light.intensity.x) * sum / (double(kSteps) * kSteps);
}

TEST(LightSampler, RectangleLightAgreesWithLambertsFormulaThreeWays) {
  const Light light =
      area_light({0.3, 1.0, 0.2}, {0.1, 0, 0.3}, AreaShape::kRectangle, 1.2, 0.6, 4);
  const double expected =
      test::polygon_irradiance(outline(light), 4, Vec3d(kShadingPoint), Vec3d(kTilted));
  expect_agree(estimate(scene_of(light), kShadingPoint, kTilted), expected, "rectangle");
}

TEST(LightSampler, EllipseLightAgreesWithLambertsFormulaThreeWays) {
  const Light light = area_light({-0.2, 0.8, 0.3}, {0, 0, 0.5}, AreaShape::kEllipse, 1.0, 0.5, 4);
  const double expected =
      test::polygon_irradiance(outline(light), 4, Vec3d(kShadingPoint), Vec3d(kTilted));
  expect_agree(estimate(scene_of(light), kShadingPoint, kTilted), expected, "ellipse");
}

// Spread narrows where the light goes without changing its power: for a rectangle of spread 30
// degrees and a disk of 60, off the light's axis, the three estimates meet the quadrature (whose
// attenuation is Cycles' own expression of it).
TEST(LightSampler, AreaLightsWithSpreadAgreeWithQuadratureThreeWays) {
  const Light rectangle = area_light({0.3, 1.0, 0.2}, {0.3, 0, 0.2}, AreaShape::kRectangle, 1.6,
                                     0.9, 4, 30 * kPiD / 180);
  const Light disk =
      area_light({-0.2, 0.8, 0.3}, {-0.2, 0, 0.3}, AreaShape::kEllipse, 1.0, 1.0, 4, kPiD / 3);
  for (const Light& light : {rectangle, disk}) {
    const double expected = area_light_quadrature(light, Vec3d(kShadingPoint), Vec3d(kTilted));
    ASSERT_GT(expected, 0.1);
    expect_agree(estimate(scene_of(light), kShadingPoint, kTilted), expected,
                 light.area_shape == AreaShape::kEllipse ? "disk, spread 60" : "rectangle, 30");
  }
  // Beyond the spread's reach nothing arrives, by any estimate.
  const Estimates outside = estimate(scene_of(rectangle), {3.f, 0.f, 0.2f}, {0.f, 1.f, 0.f});
  EXPECT_EQ(outside.light, 0.0);
  EXPECT_EQ(outside.bsdf, 0.0);
}

// The attenuation keeps an area light's power: its cosine-weighted integral over the hemisphere is
// pi for every spread, and at normal incidence it is tan h / (tan h - h).
TEST(LightSampler, SpreadAttenuationKeepsTheLightsPower) {
  for (double spread_deg : {1.0, 10.0, 30.0, 90.0, 150.0, 180.0}) {
    const AreaLight light({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 1, 1, false,
                          spread_deg * kPiD / 180);
    constexpr int kSteps = 200000;
    double integral = 0;
    for (int i = 0; i < kSteps; ++i) {
      const double theta = (i + 0.5) / kSteps * kPiD / 2;
      integral += light.spread_attenuation(float(std::cos(theta))) * std::cos(theta) *
                  std::sin(theta) * 2 * kPiD * (kPiD / 2 / kSteps);
    }
    EXPECT_NEAR(integral, kPiD, 2e-3 * kPiD) << spread_deg << " degrees";
    EXPECT_NEAR(light.spread_attenuation(1.f),
                cycles_spread_attenuation(1, spread_deg * kPiD / 180),
                1e-4 * light.spread_attenuation(1.f))
        << spread_deg << " degrees";
  }
}

// A point light of radius r: the disk facing p, of radiance I / (pi r^2), is the 4096-gon's.
TEST(LightSampler, SoftPointLightAgreesWithLambertsFormulaThreeWays) {
  Light light = point_light(2, {0.4, 1.1, -0.2});
  light.radius_m = 0.3;
  const Vec3d centre = light.world_from_light.point({0, 0, 0}), p(kShadingPoint);
  const Frame facing{Vec3f(normalize(p - centre))};
  std::vector<Vec3d> disk;
  for (int i = 0; i < 4096; ++i) {
    const double a = 2 * kPiD * i / 4096;
    disk.push_back(centre + (Vec3d(facing.s) * std::cos(a) + Vec3d(facing.t) * std::sin(a)) * 0.3);
  }
  const double expected = test::polygon_irradiance(disk, 2 / (kPiD * 0.09), p, Vec3d(kTilted));
  expect_agree(estimate(scene_of(light), kShadingPoint, kTilted), expected, "point, r 0.3");
}

// A spot of radius r: each point of the disk is as bright as the spot's falloff in its direction
// to p (Cycles' spot_light_attenuation of -D); p near the blend, where that varies over the disk.
TEST(LightSampler, SoftSpotAgreesWithQuadratureThreeWays) {
  Light light = point_light(3, {0, 1.2, 0});
  light.type = LightType::kSpot;
  light.spot_falloff = SpotFalloff::kCycles;
  light.world_from_light = Transform::look_at({0, 1.2, 0}, {0.9, 0, 0}, {0, 0, 1});
  light.spot_outer_angle_rad = 0.6, light.spot_blend = 0.5;
  light.radius_m = 0.25;
  const Vec3d centre(0, 1.2, 0), p(kShadingPoint), axis = normalize(Vec3d(0.9, -1.2, 0));
  const Vec3d to_p = normalize(p - centre);
  const Frame facing{Vec3f(to_p)};
  const double cos_edge = std::cos(0.6), smooth = (1 - cos_edge) * 0.5;
  constexpr int kSteps = 1000;
  double sum = 0;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const double r = (i + 0.5) / kSteps * 0.25, a = (j + 0.5) / kSteps * 2 * kPiD;
      const Vec3d x = centre + (Vec3d(facing.s) * std::cos(a) + Vec3d(facing.t) * std::sin(a)) * r;
      const Vec3d d = p - x;
      const double distance = length(d), cos_spot = dot(axis, d) / distance;
      double falloff = 0;
      if (cos_spot > cos_edge) {
        const double t = std::min(1.0, (cos_spot - cos_edge) / smooth);
        falloff = cos_spot * t * t * (3 - 2 * t);
      }
      const double cos_p = -dot(Vec3d(kTilted), d) / distance, cos_light = dot(to_p, d) / distance;
      if (cos_p > 0) sum += falloff * cos_p * cos_light / (distance * distance) * r;
    }
  const double expected = 3 / (kPiD * 0.0625) * sum * (0.25 / kSteps) * (2 * kPiD / kSteps);
  ASSERT_GT(expected, 0.1);
  expect_agree(estimate(scene_of(light), kShadingPoint, kTilted), expected, "spot, r 0.25");
}

// A sun of angle a on a tilted surface: S / (pi tan^2(a/2)) times the integral of max(0, n . w)
// over the disk of radius tan(a/2) one unit away (w the direction through each of its points).
TEST(LightSampler, SunWithAnAngleAgreesWithQuadratureThreeWays) {
  Light sun = point_light(3, {0, 0, 0});
  sun.type = LightType::kDirectional;
  sun.world_from_light = Transform::look_at({0, 0, 0}, {-0.3, -1, 0.2}, {0, 0, 1});
  sun.angle_rad = 20 * kPiD / 180;
  const Vec3d towards = normalize(Vec3d(0.3, 1, -0.2)), n(normalize(Vec3d(0.9, 1, 0)));
  const Frame frame{Vec3f(towards)};
  const double t = std::tan(sun.angle_rad / 2);
  constexpr int kSteps = 1000;
  double sum = 0;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const double r = (i + 0.5) / kSteps * t, a = (j + 0.5) / kSteps * 2 * kPiD;
      const Vec3d w =
          normalize(towards + (Vec3d(frame.s) * std::cos(a) + Vec3d(frame.t) * std::sin(a)) * r);
      sum += std::max(0.0, dot(n, w)) * r;
    }
  const double expected = 3 / (kPiD * t * t) * sum * (t / kSteps) * (2 * kPiD / kSteps);
  expect_agree(estimate(scene_of(sun), kShadingPoint, Vec3f(n)), expected, "sun, 20 degrees");
}

// For every light with a size, the ray along a light sample's direction crosses that light at the
// sampled distance, with the sample's radiance and pdf (the light choice included).
TEST(LightSampler, CrossingsReportTheDensityTheirPointIsSampledWith) {
  Light soft_point = point_light(2, {0.4, 1.1, -0.2});
  soft_point.radius_m = 0.3;
  Light sun = point_light(3, {0, 0, 0});
  sun.type = LightType::kDirectional;
  sun.world_from_light = Transform::look_at({0, 0, 0}, {-0.3, -1, 0.2}, {0, 0, 1});
  sun.angle_rad = 0.3;
  const Light lights[] = {
      soft_point, sun,
      area_light({0.3, 1.0, 0.2}, {0.1, 0, 0.3}, AreaShape::kRectangle, 1.2, 0.6, 4),
      area_light({0.3, 1.0, 0.2}, {0.3, 0, 0.2}, AreaShape::kRectangle, 1.6, 0.9, 4, 0.5),
      area_light({-0.2, 0.8, 0.3}, {0, 0, 0.5}, AreaShape::kEllipse, 1.0, 0.5, 4, 1.0)};
  for (size_t l = 0; l < std::size(lights); ++l) {
    const Scene scene = scene_of(lights[l]);
    const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
    const LightSampler sampler(scene, Transform(), geometry, 0.0);
    int checked = 0;
    for (int i = 0; i < 32; ++i)
      for (int j = 0; j < 32; ++j) {
        const float u[3] = {0.01f, (i + 0.5f) / 32, (j + 0.5f) / 32};  // the light under test
        fb_light_sample s;
        if (!sampler.sample(kShadingPoint, u, s)) continue;
        ASSERT_EQ(s.is_delta, 0u) << "light " << l;
        fb_ray ray{};
        kShadingPoint.store(ray.origin);
        for (int k = 0; k < 3; ++k)
          ray.direction[k] = s.direction[k];
        ray.t_max = HUGE_VALF;
        fb_light_crossing c[8];
        ASSERT_EQ(sampler.crossed(ray, HUGE_VALF, c, 8), 1u) << "light " << l;
        EXPECT_NEAR(c[0].pdf, s.pdf, 2e-3f * s.pdf) << "light " << l << " at " << i << ", " << j;
        EXPECT_NEAR(c[0].radiance[0], s.radiance[0], 2e-3f * s.radiance[0]) << "light " << l;
        if (std::isinf(s.distance))
          EXPECT_TRUE(std::isinf(c[0].t));
        else
          EXPECT_NEAR(c[0].t, s.distance, 1e-4f * s.distance) << "light " << l;
        ++checked;
        // Nothing is found beyond a surface met before the light.
        EXPECT_EQ(sampler.crossed(ray, std::isinf(s.distance) ? 1e6f : 0.5f * s.distance, c, 8),
                  0u);
      }
    EXPECT_GT(checked, 100) << "light " << l;  // a spread of 57 degrees leaves few
  }
}

}  // namespace
}  // namespace fb
