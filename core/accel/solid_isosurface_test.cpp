// The isosurface's intersection (core/scene/isosurface.h) against its function: a sphere written
// as a function against the exact sphere, hits of a wavy surface under a transform on its level
// set (relative to the container's size) with normals against finite differences, no span missed
// that dense sampling finds, containment, `open`, CSG, and functions that give nothing to find.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "core/accel/solid_intersect.h"
#include "core/function/isosurface_function.h"
#include "core/function/user_function.h"
#include "support/finite_difference.h"
#include "support/random_rays.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;
using test::primitive;

// Programs written as the SDL reader writes them, in x, y, z.
struct Program {
  std::shared_ptr<UserFunction> f =
      std::make_shared<UserFunction>(std::vector<std::string>{"x", "y", "z"});
  Program& p(int i) { return f->push_parameter(i), *this; }
  Program& c(double v) { return f->push_constant(v), *this; }
  Program& op(FunctionOp o, int operands) { return f->apply(o, operands), *this; }
  std::shared_ptr<const UserFunction> done() { return f->finish(), f; }
};

// sqrt(x^2 + y^2 + z^2)
Program& distance_from_origin(Program& g) {
  for (int i = 0; i < 3; ++i) {
    g.p(i).op(FunctionOp::kSqr, 1);
    if (i) g.op(FunctionOp::kAdd, 2);
  }
  return g.op(FunctionOp::kSqrt, 1);
}

// |p| + 0.1 sin(5x) sin(5y) sin(5z): |grad| <= 1 + 0.5 sqrt(3) < 1.9
std::shared_ptr<const UserFunction> wavy_ball() {
  Program g;
  distance_from_origin(g);
  for (int i = 0; i < 3; ++i) {
    g.c(5).p(i).op(FunctionOp::kMultiply, 2).op(FunctionOp::kSin, 1);
    if (i) g.op(FunctionOp::kMultiply, 2);
  }
  return g.c(0.1).op(FunctionOp::kMultiply, 2).op(FunctionOp::kAdd, 2).done();
}

Solid isosurface_solid(Isosurface iso, const Transform& world_from_object = Transform()) {
  Solid s = primitive(SolidKind::kIsosurface, world_from_object);
  s.isosurface = std::make_shared<const Isosurface>(std::move(iso));
  return s;
}

Isosurface wavy_isosurface() {
  Isosurface iso;
  iso.function = wavy_ball();
  iso.threshold = 0.8;
  iso.max_gradient = 1.9;
  iso.box_lo = {-1.2, -1.2, -1.2}, iso.box_hi = {1.2, 1.2, 1.2};
  return iso;
}

const Transform kWavyPlacement = Transform::translate({0.3, -0.2, 0.1}) *
                                 Transform::rotate({0.3, 0.1, 0.2, 0.92}) *
                                 Transform::scale({2, 1.5, 1.8});

// Rays from 8 away towards the container (half-size 1.5), and points about it.
test::RaysAtABox iso_rays() {
  return test::RaysAtABox(19, {0, 0, 0}, 8, 1.5);
}

TEST(SolidIsosurface, SphereFunctionMatchesTheExactSphere) {
  Program g;
  Isosurface iso;
  iso.function = distance_from_origin(g).done();
  iso.threshold = 1;
  iso.box_lo = {-1.5, -1.5, -1.5}, iso.box_hi = {1.5, 1.5, 1.5};
  const Transform place = Transform::translate({1, 2, -1}) * Transform::scale({0.7, 0.7, 0.7});
  const RenderSolid as_function(isosurface_solid(iso, place), Transform(), kReach);
  const RenderSolid exact(primitive(SolidKind::kSphere, place), Transform(), kReach);
  test::RaysAtABox rays = iso_rays();
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    auto [o, d] = rays.next();
    o = o + Vec3d{1, 2, -1};
    const auto a = as_function.first_hit(o, d, 0), b = exact.first_hit(o, d, 0);
    ASSERT_EQ(bool(a), bool(b)) << "ray " << i;
    if (!a) continue;
    ++hits;
    EXPECT_NEAR(a->t, b->t, 1e-9) << "ray " << i;
    EXPECT_LT(length(a->normal - b->normal), 1e-6) << "ray " << i;
  }
  EXPECT_GT(hits, 100);
}

TEST(SolidIsosurface, HitsLieOnTheLevelSetAndNormalsMatchFiniteDifferences) {
  const Isosurface iso = wavy_isosurface();
  const RenderSolid solid(isosurface_solid(iso, kWavyPlacement), Transform(), kReach);
  const Transform object_from_world = kWavyPlacement.inverse();
  const auto f = [&](Vec3d world) { return isosurface_value(iso, object_from_world.point(world)); };
  // Relative to the container's size (2.4 object units across)
  const double tolerance = 1e-9 * 2.4;
  test::RaysAtABox rays = iso_rays();
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    const auto [o, d] = rays.next();
    const auto hit = solid.first_hit(o, d, 0);
    if (!hit) continue;
    ++hits;
    EXPECT_LT(std::abs(f(hit->position)), tolerance * iso.max_gradient) << "ray " << i;
    const Vec3d fd = test::central_difference_gradient(f, hit->position, 1e-6);
    EXPECT_LT(length(hit->normal - normalize(fd)), 1e-5) << "ray " << i;
  }
  EXPECT_GT(hits, 100);
}

// Where 20,000 samples of the function along the ray find the inside, the ray hits, no later.
TEST(SolidIsosurface, MissesNoSpanDenseSamplingFinds) {
  const Isosurface iso = wavy_isosurface();
  const RenderSolid solid(isosurface_solid(iso, kWavyPlacement), Transform(), kReach);
  const Transform object_from_world = kWavyPlacement.inverse();
  test::RaysAtABox rays = iso_rays();
  for (int i = 0; i < 100; ++i) {
    const auto [o, d] = rays.next();
    double first_inside = HUGE_VAL;
    for (int k = 0; k < 20000 && first_inside == HUGE_VAL; ++k) {
      const double t = 16.0 * k / 20000;
      if (isosurface_contains(iso, object_from_world.point(o + d * t))) first_inside = t;
    }
    const auto hit = solid.first_hit(o, d, 0);
    if (first_inside < HUGE_VAL) {
      ASSERT_TRUE(hit) << "ray " << i;
      EXPECT_LE(hit->t, first_inside + 1e-9) << "ray " << i;
    }
  }
}

TEST(SolidIsosurface, ContainsIsBelowTheThresholdWithinTheContainer) {
  Isosurface iso = wavy_isosurface();
  iso.sphere_container = true, iso.centre = {0.2, 0, 0}, iso.radius = 0.85;
  const RenderSolid solid(isosurface_solid(iso), Transform(), kReach);
  test::RaysAtABox points = iso_rays();
  int inside = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3d p = points.in_box(1.2);
    if (std::abs(isosurface_value(iso, p)) < 1e-6 || std::abs(length(p - iso.centre) - 0.85) < 1e-6)
      continue;
    const bool expected = isosurface_value(iso, p) < 0 && length(p - iso.centre) < 0.85;
    EXPECT_EQ(solid.contains(p), expected) << p.x << " " << p.y << " " << p.z;
    inside += expected;
  }
  EXPECT_GT(inside, 300);
}

// f = y within the box -1..1: the half of the box below y = 0. Closed, the container's walls
// bound it; open, only the plane is surface.
TEST(SolidIsosurface, OpenLeavesTheContainerOutOfTheSurface) {
  Isosurface iso;
  iso.function = Program().p(1).done();
  for (bool open : {false, true}) {
    Solid s = isosurface_solid(iso);
    s.open = open;
    const RenderSolid solid(s, Transform(), kReach);
    const auto top = solid.first_hit({0.2, 5, 0.1}, {0, -1, 0}, 0);
    ASSERT_TRUE(top);
    EXPECT_NEAR(top->t, 5, 1e-12);
    EXPECT_LT(length(top->normal - Vec3d{0, 1, 0}), 1e-9);
    const auto side = solid.first_hit({-5, -0.5, 0}, {1, 0, 0}, 0);
    EXPECT_EQ(bool(side), !open);
    if (side) {
      EXPECT_NEAR(side->t, 4, 1e-12);
      EXPECT_LT(length(side->normal - Vec3d{-1, 0, 0}), 1e-12);
    }
  }
}

// box minus a ball written as a function: from inside the box the ray meets the ball's surface,
// whose normal points out of the difference, into the ball.
TEST(SolidIsosurface, TakesPartInCsg) {
  Program g;
  Isosurface iso;
  iso.function = distance_from_origin(g).done();
  iso.threshold = 0.5;
  const Solid difference =
      test::csg(SolidKind::kIntersection,
                {primitive(SolidKind::kBox), test::inverted(isosurface_solid(iso))});
  const RenderSolid solid(difference, Transform(), kReach);
  const auto outside = solid.first_hit({0, 0, 5}, {0, 0, -1}, 0);
  ASSERT_TRUE(outside);
  EXPECT_NEAR(outside->t, 4, 1e-12);
  const auto within = solid.first_hit({0, 0, 0.9}, {0, 0, -1}, 0);
  ASSERT_TRUE(within);
  EXPECT_NEAR(within->t, 0.4, 1e-9);
  EXPECT_LT(length(within->normal - Vec3d{0, 0, -1}), 1e-6);
  EXPECT_TRUE(solid.contains({0.7, 0.7, 0}));
  EXPECT_FALSE(solid.contains({0.3, 0.1, 0}));
}

// A function that is nowhere a number (sqrt(-1 - x^2)) has no surface; with a tiny accuracy the
// walk stops at its sample cap rather than taking 10^9 steps.
TEST(SolidIsosurface, NowhereDefinedFunctionGivesNoSurfaceInBoundedTime) {
  Isosurface iso;
  iso.function = Program()
                     .c(-1)
                     .p(0)
                     .op(FunctionOp::kSqr, 1)
                     .op(FunctionOp::kSubtract, 2)
                     .op(FunctionOp::kSqrt, 1)
                     .done();
  iso.accuracy = 1e-9;
  const RenderSolid solid(isosurface_solid(iso), Transform(), kReach);
  const auto start = std::chrono::steady_clock::now();
  test::RaysAtABox rays = iso_rays();
  for (int i = 0; i < 50; ++i) {
    const auto [o, d] = rays.next();
    EXPECT_FALSE(solid.first_hit(o, d, 0));
  }
  EXPECT_FALSE(solid.contains({0, 0, 0}));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

}  // namespace
}  // namespace fb
