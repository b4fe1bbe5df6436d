// The surface of revolution (core/math/sor.h) against closed forms and its implicit function: a
// constant profile is a capped cylinder (open: no caps), and for a wavy profile hits lie where
// x^2 + z^2 - r(y)^2 changes sign or on a cap, normals match finite differences, containment
// matches the function between the caps.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/accel/solid_intersect.h"
#include "core/math/sor.h"
#include "support/finite_difference.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;
using test::primitive;

Solid sor_solid(const std::vector<std::pair<double, double>>& points, bool open = false) {
  Solid s = primitive(SolidKind::kSor);
  s.sor = sor_from_points(points);
  s.open = open;
  return s;
}

TEST(SolidSor, ConstantProfileIsACappedCylinder) {
  const Solid s = sor_solid({{1, -1}, {1, 0}, {1, 1}, {1, 2}});
  const RenderSolid solid(s, Transform(), kReach);
  const auto side = solid.first_hit({0, 0.5, 5}, {0, 0, -1}, 0);
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 4, 1e-12);
  EXPECT_LT(length(side->normal - Vec3d{0, 0, 1}), 1e-12);
  const auto cap = solid.first_hit({0.3, 5, 0.2}, {0, -1, 0}, 0);
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->t, 4, 1e-12);
  EXPECT_LT(length(cap->normal - Vec3d{0, 1, 0}), 1e-12);
  EXPECT_TRUE(solid.contains({0.5, 0.5, 0.5}));
  EXPECT_FALSE(solid.contains({0.5, 1.1, 0.5}));
  // open: through the missing caps, nothing in the way
  const RenderSolid open(sor_solid({{1, -1}, {1, 0}, {1, 1}, {1, 2}}, true), Transform(), kReach);
  EXPECT_FALSE(open.first_hit({0.3, 5, 0.2}, {0, -1, 0}, 0));
  EXPECT_TRUE(open.first_hit({0, 0.5, 5}, {0, 0, -1}, 0));
}

TEST(SolidSor, WavyProfileAgainstItsImplicitFunction) {
  const std::vector<std::pair<double, double>> points{
      {0.5, -0.5}, {0.8, 0}, {0.4, 0.5}, {1.0, 1.1}, {0.6, 1.6}, {0.7, 2.0}, {0.3, 2.4}};
  const Solid s = sor_solid(points);
  const RenderSolid solid(s, Transform(), kReach);
  const double y_lo = 0, y_hi = 2.0;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int sides = 0, caps = 0;
  for (int i = 0; i < 600; ++i) {
    const Vec3d o = normalize(Vec3d{u(rng), u(rng), u(rng)}) * 5 + Vec3d{0, 1, 0};
    const Vec3d target{u(rng) * 0.8, 1 + u(rng), u(rng) * 0.8};
    const Vec3d d = normalize(target - o);
    const auto hit = solid.first_hit(o, d, 0);
    if (!hit) continue;
    const Vec3d p = hit->position;
    if (std::abs(p.y - y_lo) < 1e-9 || std::abs(p.y - y_hi) < 1e-9) {
      ++caps;  // on a cap, within its disc
      EXPECT_LE(sor_value(s.sor, p), 1e-9);
      continue;
    }
    ++sides;
    EXPECT_GT(sor_value(s.sor, p - d * 1e-9), 0) << "ray " << i;
    EXPECT_LE(sor_value(s.sor, p + d * 1e-9), 0) << "ray " << i;
    const double h = 1e-6;
    bool near_joint = false;
    for (const auto& [r, y] : points)
      near_joint |= std::abs(p.y - y) < 2 * h;
    if (near_joint) continue;
    const auto f = [&](Vec3d q) { return sor_value(s.sor, q); };
    const Vec3d fd = test::central_difference_gradient(f, p, h);
    EXPECT_LT(length(hit->normal - normalize(fd)), 1e-5) << "ray " << i;
  }
  EXPECT_GT(sides, 150);
  EXPECT_GT(caps, 5);
  for (int i = 0; i < 3000; ++i) {
    const Vec3d p{u(rng) * 1.2, 1 + u(rng) * 1.2, u(rng) * 1.2};
    const double f = sor_value(s.sor, p);
    if (std::abs(f) < 1e-9 || std::abs(p.y - y_lo) < 1e-9 || std::abs(p.y - y_hi) < 1e-9) continue;
    EXPECT_EQ(solid.contains(p), p.y > y_lo && p.y < y_hi && f < 0)
        << p.x << " " << p.y << " " << p.z;
  }
}

}  // namespace
}  // namespace fb
