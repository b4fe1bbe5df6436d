#include "core/render/light_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <filmback/sampling.h>

#include "core/render/light_choice.h"
#include "core/render/light_sampler.h"
#include "tests/support/chi_square.h"

namespace fb {
namespace {

constexpr double kCells = double(LightChoice::kCells);

// 64 point, spot and area lights of intensities over four decades, scattered in a 10 m box, and
// two suns beside them (no place: chosen by power beside the tree).
std::vector<LightBounds> scattered_lights(std::vector<double>& power) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  std::vector<LightBounds> bounds;
  for (int i = 0; i < 64; ++i) {
    LightBounds b;
    const Vec3f at{10 * unit(rng), 10 * unit(rng), 3 * unit(rng)};
    const float reach = i % 4 == 0 ? 0.f : 0.05f * unit(rng);
    b.lo = at - Vec3f{reach, reach, reach};
    b.hi = at + Vec3f{reach, reach, reach};
    b.intensity = std::pow(10.f, 4 * unit(rng) - 2);
    b.axis = normalize(Vec3f{unit(rng) - 0.5f, unit(rng) - 0.5f, -1.f});
    b.cos_theta_o = i % 3 == 0 ? -1.f : (i % 3 == 1 ? 0.7f : 1.f);  // point, spot, area
    bounds.push_back(b);
    power.push_back(4 * std::numbers::pi * b.intensity);
  }
  for (int sun = 0; sun < 2; ++sun) {
    bounds.emplace_back();
    power.push_back(50.0);
  }
  return bounds;
}

// The points the tests look from: inside the lights' box, below and beside it.
const Vec3f kPoints[] = {{5, 5, 1}, {0.5f, 9, 0}, {-20, 3, -5}, {5, 5, -0.2f}};

// Over all lights the probabilities sum to exactly 1 (in whole cells) where every light can reach
// the point, and each probability is what choose() reports for the light it picks.
TEST(LightTree, ProbabilitiesSumToOneAndMatchTheChoice) {
  std::vector<double> power;
  const std::vector<LightBounds> bounds = scattered_lights(power);
  const LightChoice choice(power, bounds, LightSelection::kTree);
  ASSERT_TRUE(choice.uses_tree());
  for (Vec3f p : kPoints) {
    double cells = 0;
    for (uint32_t i = 0; i < bounds.size(); ++i)
      cells += double(choice.pmf(p, i)) * kCells;
    // Area lights (theta_o = 0) send nothing behind them: their cells go unused from there, and
    // then choose() finds nothing for those cells.
    uint32_t unlit_cells = 0;
    for (uint32_t cell = 0; cell < LightChoice::kCells; cell += 4099) {
      uint32_t light;
      float pmf;
      if (!choice.choose(p, float(cell) / float(kCells), light, pmf)) {
        ++unlit_cells;
        continue;
      }
      ASSERT_EQ(pmf, choice.pmf(p, light)) << "light " << light;
      ASSERT_GT(pmf, 0.f);
    }
    if (unlit_cells == 0) {
      EXPECT_EQ(cells, kCells) << "at " << p.x << ", " << p.y << ", " << p.z;
    }
    EXPECT_LE(cells, kCells);
    EXPECT_GT(cells, 0.5 * kCells);
  }
}

// The frequencies with which random u choose each light match its probability: Pearson's
// chi-square (tests/support/chi_square.h), failing a correct tree once in 10^3 seeds (this seed is
// fixed).
TEST(LightTree, ChoiceFrequenciesPassChiSquare) {
  std::vector<double> power;
  const std::vector<LightBounds> bounds = scattered_lights(power);
  const LightChoice choice(power, bounds, LightSelection::kTree);
  std::mt19937 rng(4711);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  constexpr int kSamples = 200000;
  for (Vec3f p : kPoints) {
    std::vector<double> observed(bounds.size() + 1, 0), expected(bounds.size() + 1, 0);
    for (int k = 0; k < kSamples; ++k) {
      uint32_t light;
      float pmf;
      ++observed[choice.choose(p, unit(rng), light, pmf) ? light : bounds.size()];
    }
    double total = 0;
    for (uint32_t i = 0; i < bounds.size(); ++i)
      total += expected[i] = kSamples * double(choice.pmf(p, i));
    expected.back() = kSamples - total;  // the cells that find no light
    const test::ChiSquare chi2 = test::chi_square(observed, expected);
    EXPECT_GT(chi2.dof, 20);
    EXPECT_LT(chi2.statistic, chi2.limit())
        << chi2.dof << " degrees of freedom at " << p.x << ", " << p.y << ", " << p.z;
  }
}

// A light's importance is 0 only where it sends nothing: behind a one-sided light's plane by more
// than the box's angular radius (pi/2 past its cone of normals). Inside the box's bounding sphere
// (radius sqrt 2 here) any direction may be the light's, so nothing there is 0.
TEST(LightTree, ImportanceVanishesOnlyWhereNoLightGoes) {
  LightBounds area;
  area.lo = {-1, -1, 0}, area.hi = {1, 1, 0};
  area.intensity = 1;
  area.axis = {0, 0, -1};  // shines down
  EXPECT_GT(importance(area, {0, 0, -1}), 0.f);
  EXPECT_GT(importance(area, {5, 0, -0.01f}), 0.f);
  EXPECT_GT(importance(area, {0, 0, 1}), 0.f);  // within the bounding sphere
  EXPECT_EQ(importance(area, {0, 0, 3}), 0.f);
  EXPECT_EQ(importance(area, {5, 0, 4}), 0.f);  // 116 degrees past the normal, less 13 for the box
  area.two_sided = true;
  EXPECT_GT(importance(area, {0, 0, 3}), 0.f);
  // A point light far away brings what a point light brings: I / d^2.
  LightBounds point;
  point.lo = point.hi = {0, 0, 0};
  point.intensity = 3;
  point.cos_theta_o = -1;
  EXPECT_FLOAT_EQ(importance(point, {0, 4, 0}), 3.f / 16.f);
}

Light lamp_at(Vec3d at, float watts_per_sr, double radius_m) {
  Light light;
  light.intensity = Rgb(watts_per_sr, watts_per_sr, watts_per_sr);
  light.world_from_light = Transform::translate(at);
  light.radius_m = radius_m;
  return light;
}

// 64 small lamps (points and spheres of 1 to 3 cm, 0.01 to 100 W/sr) 1 to 3 m above the floor.
Scene many_small_lamps() {
  Scene scene;
  std::mt19937 rng(64);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 64; ++i)
    scene.lights.push_back(lamp_at({8 * unit(rng) - 4, 8 * unit(rng) - 4, 1.0 + 2.0 * unit(rng)},
                                   float(std::pow(10.0, 4 * unit(rng) - 2)),
                                   i % 2 ? 0.01 + 0.02 * unit(rng) : 0.0));
  return scene;
}

// Irradiance on the floor (z = 0, facing up) under the 64 lamps, by light sampling with `n`
// samples (u from a fixed-seed generator), with its standard error.
struct Estimate {
  double mean, standard_error;
};
Estimate floor_irradiance(const LightSampler& sampler, Vec3f at, int n) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  double sum = 0, sum2 = 0;
  for (int k = 0; k < n; ++k) {
    const float u[3] = {unit(rng), unit(rng), unit(rng)};
    fb_light_sample s;
    double e = 0;
    if (sampler.sample(at, u, s) && s.direction[2] > 0.f)
      e = double(s.radiance[0]) * s.direction[2] / s.pdf;
    sum += e, sum2 += e * e;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

// Both samplers estimate the analytic irradiance E = sum I cos / d^2 (the spheres: the facing
// disks' I cos / (d^2 + r^2) at normal incidence, Cycles 3.4's; here d >> r, so the disks' exact
// form factor is used), within 4.5 standard errors; the tree with a smaller error.
TEST(LightTree, ManyLampsLightTheFloorAsLambertSays) {
  const Scene scene = many_small_lamps();
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler tree(scene, Transform(), geometry, 0.0, {}, LightSelection::kTree);
  const LightSampler power(scene, Transform(), geometry, 0.0, {}, LightSelection::kPower);
  ASSERT_TRUE(tree.uses_tree());
  ASSERT_FALSE(power.uses_tree());
  for (Vec3f at : {Vec3f{0, 0, 0}, Vec3f{3, -3, 0}}) {
    double expected = 0;
    for (const Light& light : scene.lights) {
      const Vec3d d = light.world_from_light.point({0, 0, 0}) - Vec3d(at);
      const double d2 = dot(d, d), r2 = light.radius_m * light.radius_m;
      // A disk facing the point, seen at angle theta off the floor's normal: its irradiance is
      // I cos(theta) / (d^2 + r^2) to first order in r^2 / d^2 off the axis (Lambert).
      expected += light.intensity.x * (d.z / std::sqrt(d2)) / (d2 + r2);
    }
    constexpr int kSamples = 40000;
    const Estimate with_tree = floor_irradiance(tree, at, kSamples);
    const Estimate by_power = floor_irradiance(power, at, kSamples);
    EXPECT_NEAR(with_tree.mean, expected, 4.5 * with_tree.standard_error + 2e-3 * expected);
    EXPECT_NEAR(by_power.mean, expected, 4.5 * by_power.standard_error + 2e-3 * expected);
    EXPECT_LT(with_tree.standard_error, by_power.standard_error);
  }
}

// What light sampling chose, a BSDF-sampled ray through the same point finds with the same pdf
// (LightSampler::crossed), the tree's choice included: MIS weights then sum to 1.
TEST(LightTree, CrossedLampsReportTheTreesProbability) {
  const Scene scene = many_small_lamps();
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0, {}, LightSelection::kTree);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  const Vec3f at{0.5f, -1, 0};
  int compared = 0;
  for (int k = 0; k < 2000; ++k) {
    const float u[3] = {unit(rng), unit(rng), unit(rng)};
    fb_light_sample s;
    if (!sampler.sample(at, u, s) || s.is_delta) continue;
    fb_ray ray{};
    at.store(ray.origin);
    std::copy(s.direction, s.direction + 3, ray.direction);
    ray.t_max = HUGE_VALF;
    fb_light_crossing crossings[8];
    const uint32_t n = sampler.crossed(ray, HUGE_VALF, crossings, 8);
    bool found = false;
    for (uint32_t i = 0; i < n; ++i)
      if (std::abs(crossings[i].t - s.distance) < 1e-4f * s.distance) {
        EXPECT_NEAR(crossings[i].pdf, s.pdf, 1e-3f * s.pdf);
        found = true;
      }
    EXPECT_TRUE(found) << "sample " << k;
    ++compared;
  }
  EXPECT_GT(compared, 500);
}

}  // namespace
}  // namespace fb
