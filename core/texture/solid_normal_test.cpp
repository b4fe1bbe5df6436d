#include "core/texture/solid_normal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/texture/solid_pattern.h"

namespace fb {
namespace {

SolidNormal normal_of(SolidPatternKind kind, double amount) {
  SolidNormal n;
  n.pattern.kind = kind;
  n.amount = amount;
  return n;
}

double length_of(Vec3d v) {
  return std::sqrt(dot(v, v));
}

// Points spread over a few units, off the lattice.
Vec3d sample_point(int i) {
  return {0.37 * i - 3.1, 0.11 * (i % 7) + 0.05, 0.23 * (i % 11) - 1.3};
}

constexpr SolidPatternKind kNormalKinds[] = {
    SolidPatternKind::kBumps,   SolidPatternKind::kDents,  SolidPatternKind::kWrinkles,
    SolidPatternKind::kRipples, SolidPatternKind::kWaves,  SolidPatternKind::kGradient,
    SolidPatternKind::kMarble,  SolidPatternKind::kBozo,   SolidPatternKind::kGranite,
    SolidPatternKind::kChecker, SolidPatternKind::kLeopard};

TEST(SolidNormal, PerturbedNormalIsUnitAndOnTheSurfacesSide) {
  // amount 0.5: the largest push (|DNoise| components <= 1, wave sums <= amount) stays below
  // the unit normal's length, so the bent normal keeps to the normal's side.
  const Vec3d up{0, 1, 0};
  for (SolidPatternKind kind : kNormalKinds) {
    const SolidNormal n = normal_of(kind, 0.5);
    for (int i = 0; i < 60; ++i) {
      const Vec3d bent = perturbed_normal(n, sample_point(i), up);
      EXPECT_NEAR(length_of(bent), 1.0, 1e-12) << int(kind) << " at " << i;
      EXPECT_GT(dot(bent, up), 0.0) << int(kind) << " at " << i;
    }
  }
}

TEST(SolidNormal, AmountZeroLeavesTheNormalAlone) {
  const Vec3d tilted = Vec3d{0.3, 0.8, -0.52} / length_of(Vec3d{0.3, 0.8, -0.52});
  for (SolidPatternKind kind : kNormalKinds) {
    SolidNormal n = normal_of(kind, 0.0);
    n.pattern.pattern_from_world = Transform::scale({3, 0.5, 2});  // no effect either
    for (int i = 0; i < 20; ++i) {
      const Vec3d bent = perturbed_normal(n, sample_point(i), tilted);
      EXPECT_NEAR(length_of(bent - tilted), 0.0, 1e-12) << int(kind) << " at " << i;
    }
  }
}

TEST(SolidNormal, BumpsAddAmountTimesTheVectorNoise) {
  const Vec3d up{0, 1, 0};
  const SolidNormal n = normal_of(SolidPatternKind::kBumps, 0.7);
  double largest_tilt = 0;
  for (int i = 0; i < 40; ++i) {
    const Vec3d p = sample_point(i);
    const Vec3d expected = up + solid::vector_noise(p) * 0.7;
    const Vec3d bent = perturbed_normal(n, p, up);
    EXPECT_NEAR(length_of(bent - expected / length_of(expected)), 0.0, 1e-12) << i;
    largest_tilt = std::max(largest_tilt, 1 - bent.y);
  }
  EXPECT_GT(largest_tilt, 0.01);  // the bumps do bend the normal
}

// Ripples and waves push the normal by the gradient of a height field of concentric cosines:
// H = -amount / (2 pi f N) sum cos(2 pi (|d| f w + phase)) / w^2 (w = 1 for ripples).
double wave_height(const SolidNormal& n, Vec3d p, bool waves) {
  double h = 0;
  for (const solid::WaveSource& s : solid::wave_sources()) {
    const Vec3d d = p - s.centre;
    const double w = waves ? s.frequency : 1.0, f = n.pattern.frequency;
    h -= std::cos(2 * std::numbers::pi * (length_of(d) * f * w + n.pattern.phase)) /
         (2 * std::numbers::pi * f * w * w * solid::kWaveSources);
  }
  return h * n.amount;
}

TEST(SolidNormal, RipplesAndWavesAreTheGradientOfConcentricWaves) {
  for (bool waves : {false, true}) {
    SolidNormal n = normal_of(waves ? SolidPatternKind::kWaves : SolidPatternKind::kRipples, 0.4);
    n.pattern.frequency = 3;
    n.pattern.phase = 0.2;
    for (int i = 0; i < 30; ++i) {
      const Vec3d p = sample_point(i) * 0.7 + Vec3d{2, 0, 1};
      constexpr double h = 1e-5;
      const Vec3d gradient{
          (wave_height(n, p + Vec3d{h, 0, 0}, waves) - wave_height(n, p - Vec3d{h, 0, 0}, waves)),
          (wave_height(n, p + Vec3d{0, h, 0}, waves) - wave_height(n, p - Vec3d{0, h, 0}, waves)),
          (wave_height(n, p + Vec3d{0, 0, h}, waves) - wave_height(n, p - Vec3d{0, 0, h}, waves))};
      const Vec3d push = solid::normal_perturbation(n, p);
      EXPECT_NEAR(length_of(push - gradient / (2 * h)), 0.0, 1e-7) << waves << " at " << i;
    }
  }
}

TEST(SolidNormal, WrinklesPushAlongTheAbsoluteNoiseOfTenOctaves) {
  const SolidNormal n = normal_of(SolidPatternKind::kWrinkles, 1.0);
  for (int i = 0; i < 20; ++i) {
    const Vec3d push = solid::normal_perturbation(n, sample_point(i));
    // every component >= 0, and at least the first octave's |DNoise|
    const Vec3d first = solid::vector_noise(sample_point(i));
    EXPECT_GE(push.x, std::abs(first.x) - 1e-12);
    EXPECT_GE(push.y, std::abs(first.y) - 1e-12);
    EXPECT_GE(push.z, std::abs(first.z) - 1e-12);
  }
}

// A linear pattern (gradient x, ramp) differentiates exactly over the tetrahedron: the push is
// -5 amount (0.02 / accuracy) (4/3) accuracy grad = -(0.4 / 3) amount grad, whatever accuracy.
TEST(SolidNormal, OtherPatternsAreDifferentiatedNumericallyWithPovRaysScale) {
  SolidNormal n = normal_of(SolidPatternKind::kGradient, 0.6);
  n.pattern.gradient = {1, 0, 0};
  for (double accuracy : {0.02, 0.05, 0.005}) {
    n.accuracy = accuracy;
    const Vec3d push = solid::normal_perturbation(n, {0.4, 0.3, 0.7});
    EXPECT_NEAR(push.x, -0.4 / 3 * 0.6, 1e-8) << accuracy;
    EXPECT_NEAR(push.y, 0.0, 1e-8) << accuracy;
    EXPECT_NEAR(push.z, 0.0, 1e-8) << accuracy;
  }
  // A slope_map from height 1 down to 0 turns the slope over.
  n.accuracy = 0.02;
  n.slope_map = {{0.f, 1.f, -1.f}, {1.f, 0.f, -1.f}};
  EXPECT_NEAR(solid::normal_perturbation(n, {0.4, 0.3, 0.7}).x, 0.4 / 3 * 0.6, 1e-6);
}

TEST(SolidNormal, SlopeMapIsPovRaysHermiteCubic) {
  const std::vector<SolidSlopeStop> map = {{0.f, 0.f, 0.f}, {0.5f, 1.f, 0.f}, {1.f, 0.f, 0.f}};
  EXPECT_DOUBLE_EQ(solid::slope_height(map, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(solid::slope_height(map, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(solid::slope_height(map, 1.0), 0.0);
  // flat ends: smoothstep, 3 t^2 - 2 t^3 at t = 1/2 is 1/2
  EXPECT_NEAR(solid::slope_height(map, 0.25), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(solid::slope_height({}, 0.3), 0.3);
}

// A normal_map blends its entries' bent normals by where the pattern's value falls between them
// (POV-Ray's NormalBlendMap), each evaluated in the map's pattern space.
TEST(SolidNormal, NormalMapBlendsTheEntriesAboutThePatternsValue) {
  SolidNormal map = normal_of(SolidPatternKind::kGradient, 0.5);
  map.pattern.gradient = {1, 0, 0};
  SolidNormal bumps = normal_of(SolidPatternKind::kBumps, 0.5);
  SolidNormal flat = normal_of(SolidPatternKind::kBumps, 0.0);
  map.normal_map = {{0.f, bumps}, {1.f, flat}};
  const Vec3d up{0, 1, 0};
  for (double x : {0.1, 0.25, 0.6, 0.9}) {
    const Vec3d p{x, 0.37, 0.81};
    const Vec3d blend = perturbed_normal(bumps, p, up) * (1 - x) + up * x;
    const Vec3d bent = perturbed_normal(map, p, up);
    EXPECT_NEAR(length_of(bent - blend / length_of(blend)), 0.0, 1e-9) << x;
  }
  // the entries live in the map's space: scaling the map scales where they are read
  map.pattern.pattern_from_world = Transform::scale({0.5, 0.5, 0.5});
  const Vec3d p{0.5, 0.74, 1.62};  // the map's point (0.25, 0.37, 0.81)
  const Vec3d blend = perturbed_normal(bumps, p * 0.5, up) * 0.75 + up * 0.25;
  EXPECT_NEAR(length_of(perturbed_normal(map, p, up) - blend / length_of(blend)), 0.0, 1e-9);
}

// POV-Ray scales the bumps with the pattern (the normal is made unit in pattern space): a
// scaled gradient bends the normal as much as an unscaled one; no_bump_scale lets the scale in.
TEST(SolidNormal, PatternTransformsMoveTheBumpsNotTheirDepth) {
  SolidNormal n = normal_of(SolidPatternKind::kGradient, 0.5);
  n.pattern.gradient = {1, 0, 0};
  const Vec3d up{0, 1, 0}, p{0.3, 0.2, 0.1};
  const Vec3d plain = perturbed_normal(n, p, up);
  n.pattern.pattern_from_world = Transform::scale({0.5, 0.5, 0.5});  // `scale 2`
  const Vec3d scaled = perturbed_normal(n, p, up);
  EXPECT_NEAR(length_of(scaled - plain), 0.0, 1e-9);
  n.scale_bumps = false;
  const Vec3d unscaled = perturbed_normal(n, p, up);
  EXPECT_NEAR(unscaled.x / unscaled.y, 0.5 * plain.x / plain.y, 1e-9);
  // rotated 90 degrees about y, the slope runs along z instead of x
  SolidNormal r = normal_of(SolidPatternKind::kGradient, 0.5);
  r.pattern.gradient = {1, 0, 0};
  r.pattern.pattern_from_world = Transform::rotate({0, std::sqrt(0.5), 0, std::sqrt(0.5)});
  const Vec3d rotated = perturbed_normal(r, p, up);
  EXPECT_NEAR(std::abs(rotated.z), std::abs(plain.x), 1e-9);
  EXPECT_NEAR(rotated.x, 0.0, 1e-9);
}

}  // namespace
}  // namespace fb
