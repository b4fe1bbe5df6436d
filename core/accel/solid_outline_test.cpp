// The extruded outline (SolidKind::kOutline, POV-Ray's prism and text) against its definition:
// hits on the walls' curves or inside the caps, normals against the surface's finite
// differences, the inside test against a textbook point-in-polygon, rays through shared ends.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/accel/solid_intersect.h"
#include "support/outline_shapes.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;

// Relative to the outline's size (about 10): double-precision roots, transformed once.
constexpr double kOutlineSurfaceTolerance = 1e-9;

// A ray from outside the outline's box towards a random point of it.
struct OutlineTestRay {
  Vec3d o, d;
};

OutlineTestRay random_ray(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> x(-2.5, 7.5), y(-3.5, 3.5), z(-0.2, 1.2), a(0, 6.2832),
      c(-1, 1);
  const Vec3d target{x(rng), y(rng), z(rng)};
  const double cz = c(rng), sz = std::sqrt(1 - cz * cz), phi = a(rng);
  const Vec3d d{sz * std::cos(phi), sz * std::sin(phi), cz};
  return {target - d * 20.0, d};
}

TEST(SolidOutline, HitsLieOnTheWallsCurvesOrInsideTheCaps) {
  const Outline outline = test::mixed_outline();
  const RenderSolid solid(test::outline_solid(outline), Transform(), kReach);
  std::mt19937_64 rng(19);
  int walls = 0, caps = 0;
  for (int i = 0; i < 4000; ++i) {
    const OutlineTestRay r = random_ray(rng);
    const std::optional<SolidHit> hit = solid.first_hit(r.o, r.d, 0);
    if (!hit) continue;
    const Vec3d p = hit->position;
    EXPECT_LT(dot(hit->normal, r.d), 0) << "the first hit from outside faces the ray";
    const double to_cap = std::min(std::abs(p.z), std::abs(p.z - 1));
    const double to_wall = test::distance_to_curves(outline, {p.x, p.y});
    if (to_cap < to_wall) {
      ++caps;
      EXPECT_LT(to_cap, kOutlineSurfaceTolerance * 10);
      EXPECT_TRUE(outline_contains(outline, {p.x, p.y}) || to_wall < 1e-9);
      EXPECT_NEAR(std::abs(hit->normal.z), 1, 1e-12);
    } else {
      ++walls;
      EXPECT_LT(to_wall, kOutlineSurfaceTolerance * 10) << p.x << " " << p.y << " " << p.z;
      EXPECT_GE(p.z, -1e-12);
      EXPECT_LE(p.z, 1 + 1e-12);
      EXPECT_NEAR(hit->normal.z, 0, 1e-12);
    }
  }
  EXPECT_GT(walls, 500);
  EXPECT_GT(caps, 500);
}

// The normal is perpendicular to the surface traced by neighbouring parallel rays.
TEST(SolidOutline, NormalsMatchTheSurfacesFiniteDifferences) {
  const Outline outline = test::mixed_outline();
  const Transform place = Transform::translate({0.3, -0.2, 0.1}) * Transform::scale({1, 1, 2.5});
  Solid conic = test::outline_solid(outline, place);
  conic.conic = true, conic.radius0 = 0.5, conic.radius1 = 1.5;
  for (const Solid& s : {test::outline_solid(outline, place), conic}) {
    const RenderSolid solid(s, Transform(), kReach);
    std::mt19937_64 rng(21);
    int compared = 0;
    constexpr double kStep = 1e-5;
    for (int i = 0; i < 3000; ++i) {
      const OutlineTestRay r = random_ray(rng);
      const Vec3d e1 =
          normalize(cross(r.d, std::abs(r.d.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0}));
      const Vec3d e2 = cross(r.d, e1);
      const auto a = solid.first_hit(r.o, r.d, 0);
      const auto b = solid.first_hit(r.o + e1 * kStep, r.d, 0);
      const auto c = solid.first_hit(r.o + e2 * kStep, r.d, 0);
      if (!a || !b || !c) continue;
      // Only where the three rays meet one smooth piece (no edge between them).
      if (length(a->normal - b->normal) > 1e-3 || length(a->normal - c->normal) > 1e-3) continue;
      Vec3d n = normalize(cross(b->position - a->position, c->position - a->position));
      if (dot(n, a->normal) < 0) n = -n;
      EXPECT_LT(length(n - a->normal), 1e-3) << a->position.x << " " << a->position.y;
      ++compared;
    }
    EXPECT_GT(compared, 800) << (s.conic ? "conic" : "linear");
  }
}

TEST(SolidOutline, InsideTestAgreesWithPointInPolygon) {
  const Outline outline = test::mixed_outline();
  const RenderSolid solid(test::outline_solid(outline), Transform(), kReach);
  const auto polygon = test::chords(outline, 500);  // chords within 2e-5 of the curves
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> x(-3, 8), y(-4, 4), z(-0.5, 1.5);
  int inside = 0;
  for (int i = 0; i < 6000; ++i) {
    const Vec3d p{x(rng), y(rng), z(rng)};
    if (test::distance_to_curves(outline, {p.x, p.y}) < 1e-3 || std::abs(p.z) < 1e-6 ||
        std::abs(p.z - 1) < 1e-6)
      continue;  // on the boundary either answer is right
    const bool expected = p.z > 0 && p.z < 1 && test::chords_contain(polygon, {p.x, p.y});
    EXPECT_EQ(outline_contains(outline, {p.x, p.y}), test::chords_contain(polygon, {p.x, p.y}));
    ASSERT_EQ(solid.contains(p), expected) << p.x << " " << p.y << " " << p.z;
    inside += expected;
  }
  EXPECT_GT(inside, 600);  // about a seventh of the box is inside
}

// Rays through the corner two segments share, and along the outline's edges' lines, keep the
// even-odd count right: entering at the corner, not inside out.
TEST(SolidOutline, RaysThroughSharedCornersEnterAndLeaveOnce) {
  Outline square;
  const Vec2d corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int i = 0; i < 4; ++i)
    square.segments.push_back(line_segment(corners[i], corners[(i + 1) % 4]));
  finish_outline(square);
  const RenderSolid solid(test::outline_solid(square), Transform(), kReach);
  // Along the diagonal through two corners, level: enters at (1, 1) at t = 1.
  auto hit = solid.first_hit({2, 2, 0.5}, normalize(Vec3d{-1, -1, 0}), 0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, std::sqrt(2.0), 1e-12);
  // From inside the prism the next surface is the far corner, not the near one again.
  hit = solid.first_hit({0, 0, 0.5}, normalize(Vec3d{-1, -1, 0}), 0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, std::sqrt(2.0), 1e-12);
  EXPECT_GT(dot(hit->normal, Vec3d{-1, -1, 0}), 0);
  // Touching a corner from outside and staying outside: no hit where there is no inside.
  EXPECT_FALSE(solid.first_hit({2, 0, 0.5}, normalize(Vec3d{-1, 1, 0}), 0).has_value());
  EXPECT_TRUE(solid.contains({0.999, 0.999, 0.5}));
  EXPECT_FALSE(solid.contains({1.001, 1.001, 0.5}));
}

// POV-Ray's conic_sweep: the outline scaled by z, here between z = 0.5 and 1.5.
Solid conic_solid() {
  Solid s = test::outline_solid(test::mixed_outline());
  s.conic = true;
  s.radius0 = 0.5, s.radius1 = 1.5;
  return s;
}

TEST(SolidOutline, ConicHitsLieOnTheScaledCurvesOrInsideTheCaps) {
  const Outline outline = test::mixed_outline();
  const RenderSolid solid(conic_solid(), Transform(), kReach);
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> x(-3, 10), y(-4, 4), z(0.3, 1.7), c(-1, 1);
  int walls = 0, caps = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3d target{x(rng), y(rng), z(rng)};
    const Vec3d d = normalize(Vec3d{c(rng), c(rng), c(rng)});
    const auto hit = solid.first_hit(target - d * 30.0, d, 0);
    if (!hit) continue;
    const Vec3d p = hit->position;
    EXPECT_LT(dot(hit->normal, d), 0);
    const double to_cap = std::min(std::abs(p.z - 0.5), std::abs(p.z - 1.5));
    const double to_wall = test::distance_to_curves(outline, {p.x / p.z, p.y / p.z}) * p.z;
    if (to_cap < to_wall) {
      ++caps;
      EXPECT_LT(to_cap, kOutlineSurfaceTolerance * 10);
      EXPECT_NEAR(std::abs(hit->normal.z), 1, 1e-12);
    } else {
      ++walls;
      EXPECT_LT(to_wall, kOutlineSurfaceTolerance * 10) << p.x << " " << p.y << " " << p.z;
      // The normal is perpendicular to the ruling through the hit (the apex is on it).
      EXPECT_NEAR(dot(hit->normal, normalize(p)), 0, 1e-9);
    }
  }
  EXPECT_GT(walls, 500);
  EXPECT_GT(caps, 300);
}

TEST(SolidOutline, ConicInsideTestIsTheScaledSection) {
  const Outline outline = test::mixed_outline();
  const RenderSolid solid(conic_solid(), Transform(), kReach);
  const auto polygon = test::chords(outline, 500);
  std::mt19937_64 rng(27);
  std::uniform_real_distribution<double> x(-3, 10), y(-5, 5), z(0.2, 1.8);
  int inside = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3d p{x(rng), y(rng), z(rng)};
    const Vec2d section{p.x / p.z, p.y / p.z};
    if (test::distance_to_curves(outline, section) < 1e-3 || std::abs(p.z - 0.5) < 1e-6 ||
        std::abs(p.z - 1.5) < 1e-6)
      continue;
    const bool expected = p.z > 0.5 && p.z < 1.5 && test::chords_contain(polygon, section);
    ASSERT_EQ(solid.contains(p), expected) << p.x << " " << p.y << " " << p.z;
    inside += expected;
  }
  EXPECT_GT(inside, 300);
}

TEST(SolidOutline, OpenPrismHasNoCapsButTheCapsStillBoundIt) {
  Solid s = test::outline_solid(test::mixed_outline());
  s.open = true;
  const RenderSolid solid(s, Transform(), kReach);
  // Straight down through the square's ring: no cap, and the walls run along the ray.
  EXPECT_FALSE(solid.first_hit({1.5, 0, 5}, {0, 0, -1}, 0).has_value());
  // Down into the hole at a slant: the hole's wall, below the top, facing into the hole.
  const auto hit = solid.first_hit({0, 0, 1.5}, normalize(Vec3d{1, 0, -1}), 0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->position.x, 0.8, 1e-12);
  EXPECT_NEAR(hit->position.z, 0.7, 1e-12);
  EXPECT_NEAR(hit->normal.x, -1, 1e-12);
  EXPECT_TRUE(solid.contains({1.5, 0, 0.5}));
  EXPECT_FALSE(solid.contains({1.5, 0, 1.5}));
}

}  // namespace
}  // namespace fb
