// The lemon (core/math/lemon.h), the inner part of a spindle torus between two planes, against its
// implicit function: hits lie where (rho + major)^2 + z^2 - 1 changes sign or on a cap's disc,
// normals match the function's finite differences, containment matches it within the slab, and
// the torus's outer part (the "apple") is never drawn. major = 0 is the unit sphere cut by the
// planes; open lemons have no caps.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/accel/solid_intersect.h"
#include "core/math/lemon.h"
#include "support/finite_difference.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;
using test::primitive;

Solid lemon_solid(Lemon lemon, bool open = false, const Transform& place = Transform()) {
  Solid s = primitive(SolidKind::kLemon, place);
  s.lemon = lemon;
  s.open = open;
  return s;
}

TEST(SolidLemon, NoMajorRadiusIsTheUnitSphereCut) {
  const RenderSolid solid(lemon_solid({0, -0.5, 0.8}), Transform(), kReach);
  const auto side = solid.first_hit({5, 0, 0}, {-1, 0, 0}, 0);
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 4, 1e-12);
  EXPECT_LT(length(side->normal - Vec3d{1, 0, 0}), 1e-12);
  const auto cap = solid.first_hit({0.2, 0.1, 5}, {0, 0, -1}, 0);
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->t, 4.2, 1e-12);
  EXPECT_LT(length(cap->normal - Vec3d{0, 0, 1}), 1e-12);
  EXPECT_FALSE(solid.first_hit({5, 0, 0.9}, {-1, 0, 0}, 0));  // above the top plane
  const RenderSolid open(lemon_solid({0, -0.5, 0.8}, true), Transform(), kReach);
  // Down through the open top: inside the set from one open plane to the other, no surface.
  EXPECT_FALSE(open.first_hit({0.2, 0.1, 5}, {0, 0, -1}, 0));
  EXPECT_TRUE(open.contains({0.2, 0.1, 0}));
}

// Two lemons, one with its cusps within the slab (they are then its ends) and a squat one cut by
// both planes, each placed by a rotation and a non-uniform scale.
TEST(SolidLemon, AgainstItsImplicitFunction) {
  const Transform place = Transform::translate({0.3, -0.2, 0.1}) *
                          Transform::rotate({0.3, 0.1, 0.2, 0.9}) * Transform::scale({1.3, 1, 0.8});
  const Transform object_from_world = place.inverse();
  for (const Lemon lemon : {Lemon{0.6, -1, 1}, Lemon{0.2, -0.7, 0.5}}) {
    SCOPED_TRACE(lemon.major);
    const Solid s = lemon_solid(lemon, false, place);
    const RenderSolid solid(s, Transform(), kReach);
    const auto f = [&](Vec3d world) { return lemon_value(lemon, object_from_world.point(world)); };
    const auto in_slab = [&](Vec3d world) {
      const double z = object_from_world.point(world).z;
      return z >= lemon.z_low && z <= lemon.z_high;
    };
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    int sides = 0, caps = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3d o = normalize(Vec3d{u(rng), u(rng), u(rng)}) * 4;
      const Vec3d d = normalize(Vec3d{u(rng), u(rng), u(rng)} * 0.8 - o);
      const auto hit = solid.first_hit(o, d, 0);
      // Rays that miss must not cross the set: sampled along the chord.
      if (!hit) {
        for (int k = 0; k <= 400; ++k) {
          const Vec3d q = o + d * (8.0 * k / 400);
          ASSERT_FALSE(in_slab(q) && f(q) < -1e-9) << "ray " << i << " missed the lemon";
        }
        continue;
      }
      const Vec3d p = hit->position, q = object_from_world.point(p);
      if (std::abs(q.z - lemon.z_low) < 1e-9 || std::abs(q.z - lemon.z_high) < 1e-9) {
        ++caps;  // within the cap's disc
        EXPECT_LE(lemon_value(lemon, q), 1e-9) << "ray " << i;
        EXPECT_NEAR(
            std::abs(dot(hit->normal, normalize(place.normal_transform().vector({0, 0, 1})))), 1,
            1e-12);
        continue;
      }
      ++sides;
      EXPECT_NEAR(lemon_value(lemon, q), 0, 1e-9) << "ray " << i;
      EXPECT_GT(f(p - d * 1e-7), 0) << "ray " << i;
      EXPECT_LT(f(p + d * 1e-7), 0) << "ray " << i;
      if (std::hypot(q.x, q.y) < 1e-3) continue;  // at a cusp the normal is undefined
      const Vec3d fd = test::central_difference_gradient(f, p, 1e-6);
      EXPECT_LT(length(hit->normal - normalize(fd)), 1e-5) << "ray " << i;
    }
    EXPECT_GT(sides, 300);
    EXPECT_GT(caps, lemon.z_low > -1 ? 20 : -1);
    for (int i = 0; i < 4000; ++i) {
      const Vec3d p{u(rng) * 1.5, u(rng) * 1.5, u(rng) * 1.5};
      const double value = f(p);
      const double z = object_from_world.point(p).z;
      if (std::abs(value) < 1e-9 || std::abs(z - lemon.z_low) < 1e-9 ||
          std::abs(z - lemon.z_high) < 1e-9)
        continue;
      EXPECT_EQ(solid.contains(p), value < 0 && in_slab(p)) << p.x << " " << p.y << " " << p.z;
    }
  }
}

// The lemon in CSG: a lemon minus a ball through its middle is a ring whose inner wall is the
// ball's, its normal pointing into the hole.
TEST(SolidLemon, CsgWithABall) {
  Solid lemon = lemon_solid({0.4, -0.7, 0.7});
  Solid hole = test::ball({0, 0, 0}, 0.3, 1);
  hole.inverse = true;
  const RenderSolid ring(test::csg(SolidKind::kIntersection, {lemon, hole}), Transform(), kReach);
  const auto outer = ring.first_hit({3, 0, 0}, {-1, 0, 0}, 0);
  ASSERT_TRUE(outer);
  EXPECT_NEAR(outer->t, 3 - 0.6, 1e-12);  // rho = 1 - major at z = 0
  const auto inner = ring.first_hit({0, 0, 0}, {1, 0, 0}, 0);
  ASSERT_TRUE(inner);
  EXPECT_NEAR(inner->t, 0.3, 1e-12);
  EXPECT_EQ(inner->material, 1u);
  EXPECT_LT(length(inner->normal - Vec3d{-1, 0, 0}), 1e-12);
  EXPECT_FALSE(ring.contains({0, 0, 0}));
  EXPECT_TRUE(ring.contains({0.45, 0, 0}));
}

}  // namespace
}  // namespace fb
