// The sphere sweep (core/math/sphere_sweep.h): the union of the spheres swept along its spline.
// A linear sweep of equal spheres is a capsule (closed form, including rays square to its axis,
// where the envelope's polynomial vanishes); for linear, b_spline and cubic_spline sweeps of
// varying radius, hits lie where min_u |p - c(u)|^2 - r(u)^2 changes sign, normals match its
// finite differences, containment matches it, and no ray misses what sampling the function along
// it finds.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "core/accel/solid_intersect.h"
#include "core/math/sphere_sweep.h"
#include "support/finite_difference.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;
using test::primitive;

Solid sweep_solid(SweepSpline spline, const std::vector<Vec3d>& centres,
                  const std::vector<double>& radii, const Transform& place = Transform()) {
  Solid s = primitive(SolidKind::kSphereSweep, place);
  s.sweep = std::make_shared<SphereSweep>(sphere_sweep_from_spheres(spline, centres, radii));
  return s;
}

TEST(SolidSweep, TwoEqualSpheresAreACapsule) {
  const RenderSolid capsule(sweep_solid(SweepSpline::kLinear, {{-1, 0, 0}, {1, 0, 0}}, {0.5, 0.5}),
                            Transform(), kReach);
  // Square to the axis, through its middle and off it: the cylinder's wall.
  for (double x : {0.0, 0.3, -0.9}) {
    const auto hit = capsule.first_hit({x, 0, 5}, {0, 0, -1}, 0);
    ASSERT_TRUE(hit) << x;
    EXPECT_NEAR(hit->t, 4.5, 1e-12) << x;
    EXPECT_LT(length(hit->normal - Vec3d{0, 0, 1}), 1e-9) << x;
  }
  const auto slanted = capsule.first_hit({0.2, 5, 0.3}, {0, -1, 0}, 0);
  ASSERT_TRUE(slanted);
  EXPECT_NEAR(slanted->t, 5 - std::sqrt(0.25 - 0.09), 1e-12);
  // Along the axis: the end sphere.
  const auto end = capsule.first_hit({5, 0.1, 0}, {-1, 0, 0}, 0);
  ASSERT_TRUE(end);
  EXPECT_NEAR(end->t, 4 - std::sqrt(0.25 - 0.01), 1e-12);
  EXPECT_LT(length(end->normal - normalize(Vec3d{std::sqrt(0.24), 0.1, 0})), 1e-9);
  EXPECT_FALSE(capsule.first_hit({1.6, 0, 5}, {0, 0, -1}, 0));
  EXPECT_TRUE(capsule.contains({1.2, 0.1, 0.1}));
  EXPECT_FALSE(capsule.contains({0, 0.51, 0}));
}

// Degenerate splines: spheres about one centre are the largest of them (the envelope's
// polynomial vanishes: only the end spheres and the largest in between bound the set).
TEST(SolidSweep, CoincidentCentresAreTheLargestSphere) {
  const RenderSolid linear(
      sweep_solid(SweepSpline::kLinear, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {0.5, 0.8, 0.3}),
      Transform(), kReach);
  const auto hit = linear.first_hit({0.1, 0.2, 5}, {0, 0, -1}, 0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5 - std::sqrt(0.64 - 0.05), 1e-12);
  EXPECT_TRUE(linear.contains({0.7, 0, 0}));
  EXPECT_FALSE(linear.contains({0.81, 0, 0}));
  const RenderSolid spline(
      sweep_solid(SweepSpline::kBSpline, {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}},
                  {0.3, 0.3, 0.3, 0.3}),
      Transform(), kReach);
  const auto ball = spline.first_hit({1, 2, 8}, {0, 0, -1}, 0);
  ASSERT_TRUE(ball);
  EXPECT_NEAR(ball->t, 5 - 0.3, 1e-12);
  EXPECT_LT(length(ball->normal - Vec3d{0, 0, 1}), 1e-12);
}

struct SweepCase {
  const char* name;
  SweepSpline spline;
  std::vector<Vec3d> centres;
  std::vector<double> radii;
};

// Each sweep against min_u |p - c(u)|^2 - r(u)^2, placed by a rotation and a non-uniform scale.
TEST(SolidSweep, SplinesAgainstTheirImplicitFunction) {
  const std::vector<SweepCase> cases = {
      {"linear",
       SweepSpline::kLinear,
       {{-1, -0.5, 0}, {0, 0.5, 0.2}, {1, 0, -0.3}},
       {0.2, 0.45, 0.1}},
      {"b_spline",
       SweepSpline::kBSpline,
       {{-1.5, 0, 0}, {-1, 0.8, 0.2}, {0, -0.6, 0}, {1, 0.7, -0.4}, {1.5, 0, 0}},
       {0.2, 0.3, 0.5, 0.25, 0.2}},
      // A planar curve (z = 0): rays along z are square to it everywhere.
      {"cubic_spline",
       SweepSpline::kCatmullRom,
       {{-1.5, -0.5, 0}, {-1, 0, 0}, {0, 0.6, 0}, {0.8, -0.4, 0}, {1.4, 0.3, 0}, {2, 0, 0}},
       {0.1, 0.25, 0.4, 0.2, 0.35, 0.1}},
  };
  const Transform place = Transform::rotate({0.3, 0.1, 0.2, 0.9}) * Transform::scale({1.2, 1, 0.8});
  const Transform object_from_world = place.inverse();
  for (const SweepCase& c : cases) {
    SCOPED_TRACE(c.name);
    const Solid s = sweep_solid(c.spline, c.centres, c.radii, place);
    const RenderSolid solid(s, Transform(), kReach);
    const auto f = [&](Vec3d world) {
      return sphere_sweep_value(*s.sweep, object_from_world.point(world));
    };
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    int hits = 0;
    for (int i = 0; i < 1500; ++i) {
      const Vec3d o = normalize(Vec3d{u(rng), u(rng), u(rng)}) * 5;
      // Every fifth ray runs along the object's z: square to the cubic_spline's plane.
      const Vec3d d = i % 5 == 0 ? normalize(place.vector({0, 0, -1}))
                                 : normalize(Vec3d{u(rng) * 1.5, u(rng) * 0.8, u(rng) * 0.5} - o);
      const Vec3d from = i % 5 == 0 ? place.point({u(rng) * 2, u(rng), 3}) : o;
      const auto hit = solid.first_hit(from, d, 0);
      if (!hit) {
        for (int k = 0; k <= 2000; ++k)
          ASSERT_FALSE(f(from + d * (10.0 * k / 2000)) < -1e-6) << "ray " << i << " missed";
        continue;
      }
      ++hits;
      const Vec3d p = hit->position;
      EXPECT_NEAR(f(p), 0, 1e-9) << "ray " << i;
      EXPECT_GT(f(p - d * 1e-6), 0) << "ray " << i;
      EXPECT_LT(f(p + d * 1e-6), 0) << "ray " << i;
      const Vec3d fd = test::central_difference_gradient(f, p, 1e-6);
      EXPECT_LT(length(hit->normal - normalize(fd)), 1e-5) << "ray " << i;
    }
    EXPECT_GT(hits, 300);
    for (int i = 0; i < 3000; ++i) {
      const Vec3d p{u(rng) * 2.5, u(rng) * 1.5, u(rng) * 1.5};
      const double value = f(p);
      if (std::abs(value) < 1e-9) continue;
      EXPECT_EQ(solid.contains(p), value < 0) << p.x << " " << p.y << " " << p.z;
    }
  }
}

// In CSG: a capsule minus a box cut through it leaves two pieces; the cut wears the box's
// material and faces into the gap.
TEST(SolidSweep, CsgWithABox) {
  Solid capsule = sweep_solid(SweepSpline::kLinear, {{-1, 0, 0}, {1, 0, 0}}, {0.5, 0.5});
  Solid cut = primitive(SolidKind::kBox, Transform::scale({0.2, 1, 1}), 2);
  cut.inverse = true;
  const RenderSolid solid(test::csg(SolidKind::kIntersection, {capsule, cut}), Transform(), kReach);
  const auto hit = solid.first_hit({0, 0, 0}, {1, 0, 0}, 0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 0.2, 1e-12);
  EXPECT_EQ(hit->material, 2u);
  EXPECT_LT(length(hit->normal - Vec3d{-1, 0, 0}), 1e-12);
  EXPECT_FALSE(solid.contains({0.1, 0, 0}));
  EXPECT_TRUE(solid.contains({0.3, 0, 0}));
}

}  // namespace
}  // namespace fb
