// The lathe (core/scene/lathe.h) against closed forms and its own curve: a closed rectangle
// turned is a tube, an open line a cone's wall with no caps, and for a Bézier profile the hits lie
// on the turned curve, the normals are the curve's turned, and containment flips across them.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "core/accel/solid_intersect.h"
#include "core/math/polynomial.h"
#include "core/scene/lathe.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;
using test::primitive;

Solid lathe_solid(std::vector<OutlineSegment> segments) {
  Solid s = primitive(SolidKind::kLathe);
  Outline profile;
  profile.segments = std::move(segments);
  finish_outline(profile);
  s.outline = std::make_shared<const Outline>(std::move(profile));
  return s;
}

// A closed rectangle, radius 0.5 to 1, height 0 to 2, as a linear_spline repeating its first point.
Solid tube() {
  const Vec2d a{0.5, 0}, b{1, 0}, c{1, 2}, d{0.5, 2};
  return lathe_solid(
      {line_segment(a, b), line_segment(b, c), line_segment(c, d), line_segment(d, a)});
}

TEST(SolidLathe, ClosedRectangleIsATube) {
  const RenderSolid solid(tube(), Transform(), kReach);
  const auto outer = solid.first_hit({0, 1, 5}, {0, 0, -1}, 0);
  ASSERT_TRUE(outer);
  EXPECT_NEAR(outer->t, 4, 1e-12);
  EXPECT_LT(length(outer->normal - Vec3d{0, 0, 1}), 1e-12);
  const auto inner = solid.first_hit({0, 1, 0}, {1, 0, 0}, 0);  // from the hole, level
  ASSERT_TRUE(inner);
  EXPECT_NEAR(inner->t, 0.5, 1e-12);
  EXPECT_LT(length(inner->normal - Vec3d{-1, 0, 0}), 1e-12);
  const auto top = solid.first_hit({0.75, 5, 0}, {0, -1, 0}, 0);
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->t, 3, 1e-12);
  EXPECT_LT(length(top->normal - Vec3d{0, 1, 0}), 1e-12);
  const Vec3d slant = normalize(Vec3d{1, -1, 0.5});  // through the top ring's plane at a slant
  const auto ring = solid.first_hit(Vec3d{0.6, 2, 0.1} - slant * 3, slant, 0);
  ASSERT_TRUE(ring);
  EXPECT_NEAR(ring->t, 3, 1e-12);
  EXPECT_FALSE(solid.first_hit({0, 5, 0}, {0, -1, 0}, 0));  // down the hole
  EXPECT_TRUE(solid.contains({0, 1, 0.75}));
  EXPECT_FALSE(solid.contains({0, 1, 0.25}));
  EXPECT_FALSE(solid.contains({0, 2.1, 0.75}));
}

TEST(SolidLathe, OpenLineIsAConeWallWithoutCaps) {
  // From radius 1 at y = 0 to 0.5 at y = 1: inside is below the wall (POV-Ray's inside test),
  // the heights of its loose ends bound that set but are no surface.
  const RenderSolid solid(lathe_solid({line_segment({1, 0}, {0.5, 1})}), Transform(), kReach);
  EXPECT_FALSE(solid.first_hit({0, 5, 0}, {0, -1, 0}, 0));  // down the axis: no wall
  const auto wall = solid.first_hit({0.7, 5, 0}, {0, -1, 0}, 0);
  ASSERT_TRUE(wall);
  EXPECT_NEAR(wall->t, 5 - 0.6, 1e-12);  // r = 1 - y / 2 = 0.7 at y = 0.6
  EXPECT_LT(length(wall->normal - normalize(Vec3d{1, 0.5, 0})), 1e-12);
  const auto side = solid.first_hit({0, 0.5, 5}, {0, 0, -1}, 0);  // level, r = 0.75 there
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 5 - 0.75, 1e-12);
  EXPECT_TRUE(solid.contains({0.3, 0.5, 0.3}));
  EXPECT_FALSE(solid.contains({0.3, 1.5, 0.3}));
}

// An egg: one Bézier segment from the axis at y = 0 to the axis at y = 2, its height rising.
TEST(SolidLathe, BezierProfileAgainstItsCurve) {
  const OutlineSegment curve = cubic_bezier_segment({0, 0}, {1.2, 0.3}, {1.2, 1.7}, {0, 2});
  const Solid s = lathe_solid({curve});
  const RenderSolid solid(s, Transform(), kReach);
  // The curve's u at height y, where Y(u) - y changes sign (once: Y rises).
  const auto u_at = [&](double y) {
    const double c[4] = {curve.c[0].y - y, curve.c[1].y, curve.c[2].y, curve.c[3].y};
    double u[3];
    EXPECT_EQ(sign_changes(c, 3, -1e-9, 1 + 1e-9, u), 1) << y;
    return u[0];
  };
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> random(-1, 1);
  int hits = 0;
  for (int i = 0; i < 600; ++i) {
    const Vec3d o = normalize(Vec3d{random(rng), random(rng), random(rng)}) * 5 + Vec3d{0, 1, 0};
    const Vec3d target{random(rng) * 0.9, 1 + random(rng), random(rng) * 0.9};
    const Vec3d d = normalize(target - o);
    const auto hit = solid.first_hit(o, d, 0);
    if (!hit) continue;
    ++hits;
    const Vec3d p = hit->position;
    const double rho = std::hypot(p.x, p.z), u = u_at(p.y);
    EXPECT_NEAR(segment_point(curve, u).x, rho, 1e-9) << "ray " << i;
    const Vec2d tangent = segment_tangent(curve, u);
    const Vec3d n = hit->normal;
    EXPECT_NEAR((n.x * p.x + n.z * p.z) / rho * tangent.x + n.y * tangent.y, 0, 1e-9) << i;
    EXPECT_NEAR(n.x * p.z - n.z * p.x, 0, 1e-9) << "ray " << i;  // in the meridian plane
    EXPECT_FALSE(solid.contains(p + n * 1e-6)) << "ray " << i;
    EXPECT_TRUE(solid.contains(p - n * 1e-6)) << "ray " << i;
  }
  EXPECT_GT(hits, 200);
  for (int i = 0; i < 2000; ++i) {
    const Vec3d p{random(rng), 1 + random(rng) * 1.2, random(rng)};
    if (p.y <= 0 || p.y >= 2) {
      EXPECT_FALSE(solid.contains(p));
      continue;
    }
    const double margin = segment_point(curve, u_at(p.y)).x - std::hypot(p.x, p.z);
    if (std::abs(margin) < 1e-9) continue;
    EXPECT_EQ(solid.contains(p), margin > 0) << p.x << " " << p.y;
  }
}

}  // namespace
}  // namespace fb
