// The julia fractal's intersection (core/math/julia_fractal.h) against its own iteration: hits
// under a transform on the set's boundary (the inside test flips across them, within a
// millionth of the bounding radius), normals against the surface's finite differences, no span
// missed that dense sampling finds, containment, CSG, and hostile parameters in bounded time.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "core/accel/solid_intersect.h"
#include "core/math/julia_fractal.h"
#include "support/random_rays.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;
using test::primitive;

struct JuliaCase {
  std::string name;
  JuliaFractal julia;
};

JuliaFractal julia_of(double cx, double cy, double cz, double cw, JuliaAlgebra algebra, int power,
                      int iterations) {
  JuliaFractal j;
  j.c[0] = cx, j.c[1] = cy, j.c[2] = cz, j.c[3] = cw;
  j.algebra = algebra, j.power = power, j.max_iteration = iterations;
  j.least_step = 1e-3;
  julia_fractal_set_bounds(j);
  return j;
}

// objects/fractal1.pov's and fractal4.pov's sets, and one through a tilted slice.
std::vector<JuliaCase> julia_cases() {
  std::vector<JuliaCase> cases = {
      {"quaternion sqr", julia_of(-0.083, 0, -0.83, -0.025, JuliaAlgebra::kQuaternion, 2, 8)},
      {"quaternion cube", julia_of(-0.03, 0.5, -0.2, -0.5, JuliaAlgebra::kQuaternion, 3, 8)},
      {"hypercomplex sqr", julia_of(-0.745, 0, 0.113, 0.05, JuliaAlgebra::kHypercomplex, 2, 9)},
  };
  JuliaFractal tilted = julia_of(0.2, 0.1, 0.59, -0.2, JuliaAlgebra::kQuaternion, 2, 7);
  const double s = 1 / std::sqrt(1.25);
  tilted.slice[0] = 0.5 * s, tilted.slice[3] = s, tilted.slice_distance = 0.1;
  cases.push_back({"quaternion sqr, tilted slice", tilted});
  return cases;
}

Solid julia_solid(const JuliaFractal& julia, const Transform& world_from_object = Transform()) {
  Solid s = primitive(SolidKind::kJuliaFractal, world_from_object);
  s.julia = std::make_shared<const JuliaFractal>(julia);
  return s;
}

const Transform kJuliaPlacement = Transform::translate({0.3, -0.2, 0.1}) *
                                  Transform::rotate({0.3, 0.1, 0.2, 0.92}) *
                                  Transform::scale({1.5, 1.2, 1.4});

TEST(SolidJulia, HitsLieOnTheSetsBoundary) {
  for (const JuliaCase& c : julia_cases()) {
    const RenderSolid solid(julia_solid(c.julia, kJuliaPlacement), Transform(), kReach);
    const Transform object_from_world = kJuliaPlacement.inverse();
    const double eps = 1e-6 * c.julia.radius;  // relative to the set's size
    test::RaysAtABox rays(23, {0.3, -0.2, 0.1}, 10, 1.5);
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
      const auto [o, d] = rays.next();
      const auto hit = solid.first_hit(o, d, 0);
      if (!hit) continue;
      ++hits;
      const Vec3d q = object_from_world.point(hit->position);
      const Vec3d u = normalize(object_from_world.vector(d));
      EXPECT_FALSE(julia_fractal_contains(c.julia, q - u * eps)) << c.name << ", ray " << i;
      EXPECT_TRUE(julia_fractal_contains(c.julia, q + u * eps)) << c.name << ", ray " << i;
      EXPECT_LT(dot(hit->normal, d), 0) << c.name << ", ray " << i;
    }
    EXPECT_GT(hits, 40) << c.name;
  }
}

// The surface's own finite differences: rays beside the hit, 10^-6 of the radius apart, meet the
// same smooth piece of surface; the plane through the three points has the hit's normal. (Where a
// neighbour lands on another piece, its depth jumps: those are skipped, and few may be.)
TEST(SolidJulia, NormalsMatchFiniteDifferencesOfTheSurface) {
  for (const JuliaCase& c : julia_cases()) {
    const RenderSolid solid(julia_solid(c.julia, kJuliaPlacement), Transform(), kReach);
    const double h = 1e-6 * c.julia.radius;
    test::RaysAtABox rays(29, {0.3, -0.2, 0.1}, 10, 1.5);
    int compared = 0, hits = 0;
    for (int i = 0; i < 300; ++i) {
      const auto [o, d] = rays.next();
      const auto hit = solid.first_hit(o, d, 0);
      if (!hit) continue;
      ++hits;
      const Vec3d side = normalize(cross(d, std::abs(d.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0}));
      const Vec3d up = cross(d, side);
      const auto a = solid.first_hit(o + side * h, d, 0), b = solid.first_hit(o + up * h, d, 0);
      if (!a || !b || std::abs(a->t - hit->t) > 20 * h || std::abs(b->t - hit->t) > 20 * h)
        continue;
      ++compared;
      Vec3d fd = normalize(cross(a->position - hit->position, b->position - hit->position));
      if (dot(fd, d) > 0) fd = -fd;
      EXPECT_LT(length(hit->normal - fd), 2e-3) << c.name << ", ray " << i;
    }
    EXPECT_GT(compared, 0.8 * hits) << c.name;
  }
}

// Where 20,000 samples of the iteration along the ray find the inside, the ray hits, no later.
TEST(SolidJulia, MissesNoSpanDenseSamplingFinds) {
  for (const JuliaCase& c : julia_cases()) {
    const RenderSolid solid(julia_solid(c.julia, kJuliaPlacement), Transform(), kReach);
    const Transform object_from_world = kJuliaPlacement.inverse();
    test::RaysAtABox rays(31, {0.3, -0.2, 0.1}, 10, 1.5);
    for (int i = 0; i < 60; ++i) {
      const auto [o, d] = rays.next();
      double first_inside = HUGE_VAL;
      for (int k = 0; k < 20000 && first_inside == HUGE_VAL; ++k) {
        const double t = 20.0 * k / 20000;
        if (julia_fractal_contains(c.julia, object_from_world.point(o + d * t))) first_inside = t;
      }
      const auto hit = solid.first_hit(o, d, 0);
      if (first_inside < HUGE_VAL) {
        ASSERT_TRUE(hit) << c.name << ", ray " << i;
        EXPECT_LE(hit->t, first_inside + 1e-9) << c.name << ", ray " << i;
      }
    }
  }
}

TEST(SolidJulia, ContainsIsTheIteration) {
  const JuliaFractal julia = julia_cases()[0].julia;
  const RenderSolid solid(julia_solid(julia), Transform(), kReach);
  test::RaysAtABox points(37, {0, 0, 0}, 5, 1);
  int inside = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3d p = points.in_box(julia.radius);
    const bool expected = julia_fractal_contains(julia, p);
    EXPECT_EQ(solid.contains(p), expected) << p.x << " " << p.y << " " << p.z;
    inside += expected;
  }
  EXPECT_GT(inside, 20);
}

// The set cut by the plane z = 0 (intersection with the half-space z <= 0): from above, the ray
// meets the cut face where the set holds the point, with the plane's normal.
TEST(SolidJulia, TakesPartInCsg) {
  const JuliaFractal julia = julia_cases()[0].julia;
  const Solid cut =
      test::csg(SolidKind::kIntersection, {julia_solid(julia), primitive(SolidKind::kHalfSpace)});
  const RenderSolid solid(cut, Transform(), kReach);
  test::RaysAtABox points(41, {0, 0, 0}, 5, 1);
  int on_face = 0;
  for (int i = 0; i < 400; ++i) {
    Vec3d p = points.in_box(1);
    p.z = 0;
    if (!julia_fractal_contains(julia, p) || !julia_fractal_contains(julia, p + Vec3d{0, 0, -1e-6}))
      continue;
    const auto hit = solid.first_hit(p + Vec3d{0, 0, 5}, {0, 0, -1}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5, 1e-9);
    EXPECT_LT(length(hit->normal - Vec3d{0, 0, 1}), 1e-12);
    ++on_face;
  }
  EXPECT_GT(on_face, 10);
}

// The most iterations and the finest step the reader allows: every ray's work stays bounded.
TEST(SolidJulia, HostileParametersStayBounded) {
  JuliaFractal julia = julia_cases()[0].julia;
  julia.max_iteration = kJuliaMaxIterations;
  julia.least_step = 2 * julia.radius / kJuliaMaxSamples;
  const RenderSolid solid(julia_solid(julia), Transform(), kReach);
  const auto start = std::chrono::steady_clock::now();
  test::RaysAtABox rays(43, {0, 0, 0}, 8, 1.5);
  for (int i = 0; i < 50; ++i) {
    const auto [o, d] = rays.next();
    const auto hit = solid.first_hit(o, d, 0);
    if (hit) {
      EXPECT_TRUE(std::isfinite(hit->t) && std::isfinite(hit->normal.x));
    }
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

}  // namespace
}  // namespace fb
