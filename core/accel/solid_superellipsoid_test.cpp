// The superellipsoid's intersection against its implicit function (core/math/superellipsoid.h):
// hits on the surface, normals against finite differences, containment against the sign of f,
// and no span missed that dense sampling of f along the ray finds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/accel/solid_intersect.h"
#include "core/math/superellipsoid.h"
#include "support/finite_difference.h"
#include "support/random_rays.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;
using test::primitive;

// Shapes from rounded boxes to pinched stars, as the sample scenes use them.
constexpr SuperellipsoidExponents kShapes[] = {{1, 1},      {0.25, 0.25}, {0.2, 2.5}, {2.5, 0.5},
                                               {3.5, 0.25}, {2.5, 2.5},   {0.5, 3.5}, {0.01, 0.01}};

// Placed off the origin, scaled by 2.5 (uniformly, so object-space gradients are world normals).
constexpr double kScale = 2.5;
const Vec3d kCentre{1, -2, 3};

Solid superellipsoid(SuperellipsoidExponents s) {
  Solid solid =
      primitive(SolidKind::kSuperellipsoid,
                Transform::translate(kCentre) * Transform::scale({kScale, kScale, kScale}));
  solid.radius0 = s.e, solid.radius1 = s.n;
  return solid;
}

Vec3d object_point(Vec3d world) {
  return (world - kCentre) / kScale;
}

// Rays from a sphere around the shape towards random points of its box.
test::RaysAtABox superellipsoid_rays() {
  return test::RaysAtABox(19, kCentre, 3 * kScale, kScale);
}

TEST(SolidSuperellipsoid, HitsLieOnTheImplicitSurface) {
  for (const SuperellipsoidExponents s : kShapes) {
    const RenderSolid solid(superellipsoid(s), Transform(), kReach);
    test::RaysAtABox rays = superellipsoid_rays();
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
      const auto [o, d] = rays.next();
      const auto hit = solid.first_hit(o, d, 0);
      if (!hit) continue;
      ++hits;
      // Within 1e-9 of the shape's size along the ray: outside just before, inside just after.
      const double step = 1e-9 * kScale;
      EXPECT_GT(superellipsoid_value(s, object_point(hit->position - d * step)), 0)
          << s.e << " " << s.n << " ray " << i;
      EXPECT_LE(superellipsoid_value(s, object_point(hit->position + d * step)), 0)
          << s.e << " " << s.n << " ray " << i;
    }
    EXPECT_GT(hits, 100) << s.e << " " << s.n;
  }
}

TEST(SolidSuperellipsoid, NormalsMatchFiniteDifferences) {
  for (const SuperellipsoidExponents s : kShapes) {
    if (s.e < 0.1) continue;  // a box to rounding: its f has no useful finite differences
    const RenderSolid solid(superellipsoid(s), Transform(), kReach);
    test::RaysAtABox rays = superellipsoid_rays();
    int checked = 0;
    for (int i = 0; i < 400; ++i) {
      const auto [o, d] = rays.next();
      const auto hit = solid.first_hit(o, d, 0);
      if (!hit) continue;
      const Vec3d p = object_point(hit->position);
      // Away from the cusps and the planes where |x|^(2/e) is not differentiable.
      if (std::abs(p.x) < 1e-2 || std::abs(p.y) < 1e-2 || std::abs(p.z) < 1e-2) continue;
      const double h = 1e-7;
      const auto f = [&](Vec3d q) { return superellipsoid_value(s, q); };
      const Vec3d fd = test::central_difference_gradient(f, p, h);
      EXPECT_LT(length(hit->normal - normalize(fd)), 1e-4)
          << s.e << " " << s.n << " at " << p.x << " " << p.y << " " << p.z;
      ++checked;
    }
    EXPECT_GT(checked, 50) << s.e << " " << s.n;
  }
}

TEST(SolidSuperellipsoid, ContainsAgreesWithTheImplicitFunction) {
  for (const SuperellipsoidExponents s : kShapes) {
    const RenderSolid solid(superellipsoid(s), Transform(), kReach);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.2, 1.2);
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3d p{u(rng), u(rng), u(rng)};
      const double f = superellipsoid_value(s, p);
      if (std::abs(f) < 1e-9) continue;  // on the surface: either answer
      EXPECT_EQ(solid.contains(kCentre + p * kScale), f <= 0)
          << s.e << " " << s.n << " at " << p.x << " " << p.y << " " << p.z << " f " << f;
      inside += f <= 0;
    }
    EXPECT_GT(inside, 20) << s.e << " " << s.n;
  }
}

// Wherever 8,000 samples of f along the ray find the inside by a margin, the ray hits, and no
// sooner than the first such sample's bracket allows.
TEST(SolidSuperellipsoid, MissesNoSpanDenseSamplingFinds) {
  for (const SuperellipsoidExponents s : kShapes) {
    const RenderSolid solid(superellipsoid(s), Transform(), kReach);
    test::RaysAtABox rays = superellipsoid_rays();
    for (int i = 0; i < 150; ++i) {
      auto [o, d] = rays.next();
      // Aim near the surface: grazing rays are the hard ones.
      const Vec3d towards = kCentre + rays.direction() * (0.9 * kScale);
      d = normalize(towards - o);
      constexpr int kSamples = 8000;
      const double length_t = 6 * kScale;
      double first_inside = -1;
      for (int k = 0; k < kSamples && first_inside < 0; ++k) {
        const double t = length_t * k / kSamples;
        if (superellipsoid_value(s, object_point(o + d * t)) < -1e-3) first_inside = t;
      }
      const auto hit = solid.first_hit(o, d, 0);
      if (first_inside < 0) continue;
      ASSERT_TRUE(hit) << s.e << " " << s.n << " ray " << i;
      EXPECT_LE(hit->t, first_inside) << s.e << " " << s.n << " ray " << i;
    }
  }
}

TEST(SolidSuperellipsoid, RayFromInsideExitsAndCutWindowsAgree) {
  const SuperellipsoidExponents s{0.3, 0.3};
  const RenderSolid solid(superellipsoid(s), Transform(), kReach);
  const auto exit = solid.first_hit(kCentre, {1, 0, 0}, 0);
  ASSERT_TRUE(exit);
  EXPECT_NEAR(exit->t, kScale, 1e-12 * kScale);  // |x| = 1 at y = z = 0
  EXPECT_LT(length(exit->normal - Vec3d{1, 0, 0}), 1e-12);
  // A window cut short of the hit finds nothing; cut past it, the same hit bit for bit.
  const Vec3d o = kCentre + Vec3d{-3 * kScale, 0.3, 0.2};
  const auto whole = solid.first_hit(o, {1, 0, 0}, 0);
  ASSERT_TRUE(whole);
  EXPECT_FALSE(solid.first_hit(o, {1, 0, 0}, 0, whole->t * 0.999));
  const auto cut = solid.first_hit(o, {1, 0, 0}, 0, whole->t * 1.5);
  ASSERT_TRUE(cut);
  EXPECT_EQ(cut->t, whole->t);
}

}  // namespace
}  // namespace fb
