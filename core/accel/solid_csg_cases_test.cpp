// The hard cases of ray-interval CSG (issue 17): coincident surfaces, grazing rays, nested
// differences and intersections, rays starting inside; a window cut at Embree's tfar gives the
// uncut window's hit; trees past the stack buffer, and past what the intersector holds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/accel/solid_intersect.h"
#include "core/util/error.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::ball;
using test::csg;
using test::inverted;
using test::kReach;
using test::primitive;

const Vec3d kPlusX{1, 0, 0}, kMinusX{-1, 0, 0};

// A box [lo, hi] on x, [-h, h] on y and z.
Solid slab_box(double lo, double hi, double h, uint32_t material) {
  return primitive(
      SolidKind::kBox,
      Transform::translate({0.5 * (lo + hi), 0, 0}) * Transform::scale({0.5 * (hi - lo), h, h}),
      material);
}

struct Expected {
  double x;
  uint32_t material;
  Vec3d normal;
};

void expect_hit(const RenderSolid& solid, Vec3d o, Vec3d d, const Expected& e,
                const std::string& what) {
  const auto hit = solid.first_hit(o, d, 0);
  ASSERT_TRUE(hit) << what;
  EXPECT_NEAR(hit->position.x, e.x, 1e-14) << what;
  EXPECT_EQ(hit->material, e.material) << what;
  EXPECT_NEAR(length(hit->normal - e.normal), 0, 1e-14) << what;
}

TEST(SolidCsgCases, CoincidentFacesOfAUnionAreNoSurface) {
  // [-1, 1] and [1, 3] on x share the face x = 1, which bounds neither side of the union.
  const RenderSolid solid(csg(SolidKind::kUnion, {slab_box(-1, 1, 1, 1), slab_box(1, 3, 1, 2)}),
                          Transform(), kReach);
  expect_hit(solid, {-5, 0, 0}, kPlusX, {-1, 1, kMinusX}, "from outside");
  expect_hit(solid, {0, 0.5, 0}, kPlusX, {3, 2, kPlusX}, "from inside, across the shared face");
  expect_hit(solid, {2, 0.5, 0}, kMinusX, {-1, 1, kMinusX}, "back across it");
}

TEST(SolidCsgCases, CoincidentFaceOfADifferenceIsRemoved) {
  // [-1, 1]^3 minus [0, 1] x [-2, 2]^2: the faces at x = 1 coincide and both go; what is left
  // is [-1, 0], whose face at x = 0 is the subtracted box's, its normal turned out of the set.
  const RenderSolid solid(
      csg(SolidKind::kIntersection, {slab_box(-1, 1, 1, 1), inverted(slab_box(0, 1, 2, 2))}),
      Transform(), kReach);
  expect_hit(solid, {5, 0, 0}, kMinusX, {0, 2, kPlusX}, "through the coincident face");
  expect_hit(solid, {5, 0.99, 0.99}, kMinusX, {0, 2, kPlusX}, "near its corner");
  expect_hit(solid, {-5, 0, 0}, kPlusX, {-1, 1, kMinusX}, "from the other side");
  EXPECT_FALSE(solid.first_hit({0.5, 0, 0}, kPlusX, 0)) << "from inside the removed part";
}

TEST(SolidCsgCases, IdenticalSetsGiveTheFirstChildsSurface) {
  for (SolidKind kind : {SolidKind::kUnion, SolidKind::kIntersection}) {
    const RenderSolid solid(csg(kind, {ball({0, 0, 0}, 1, 1), ball({0, 0, 0}, 1, 2)}), Transform(),
                            kReach);
    expect_hit(solid, {-5, 0, 0}, kPlusX, {-1, 1, kMinusX}, "entering");
    expect_hit(solid, {0, 0, 0}, kPlusX, {1, 1, kPlusX}, "from the centre");
  }
  // A set minus itself is empty, whatever the rounding.
  const Solid a = ball({0.1, 0.2, 0.3}, 0.7, 1);
  const RenderSolid nothing(csg(SolidKind::kIntersection, {a, inverted(a)}), Transform(), kReach);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    const Vec3d o{3 * u(rng), 3 * u(rng), 3 * u(rng)};
    EXPECT_FALSE(nothing.first_hit(o, normalize(Vec3d{0.1, 0.2, 0.3} - o), 0));
  }
}

TEST(SolidCsgCases, GrazingRaysGiveTheLimitOrNothing) {
  // Tangent to a ball inside a union with a box beyond it: the ball adds no hit, the box does.
  const RenderSolid solid(csg(SolidKind::kUnion, {ball({0, 0, 0}, 1, 1), slab_box(2, 3, 2, 2)}),
                          Transform(), kReach);
  expect_hit(solid, {-5, 1, 0}, kPlusX, {2, 2, kMinusX}, "tangent to the ball");
  // Along the plane of the box's top face: the box's side is entered at its edge.
  const auto along_top = solid.first_hit({1.5, 0, 2}, kPlusX, 0);
  ASSERT_TRUE(along_top);
  EXPECT_EQ(along_top->position.x, 2);
  EXPECT_EQ(along_top->normal.x, -1);
  // Just outside the tangent line and just inside it, the ball's chord shrinks to its limit.
  expect_hit(solid, {-5, 1 + 1e-12, 0}, kPlusX, {2, 2, kMinusX}, "just past the ball");
  const auto inside = solid.first_hit({-5, 1 - 1e-12, 0}, kPlusX, 0);
  ASSERT_TRUE(inside);
  EXPECT_EQ(inside->material, 1u);
  EXPECT_NEAR(inside->position.x, 0, 2e-6);  // chord half-length sqrt(2e-12)
}

TEST(SolidCsgCases, NestedDifferencesAndIntersections) {
  // On the x axis: A = [-2, 2], B = [0.5, 2.5], C = [-1.5, -0.5], E = [-1.75, 0.25], F =
  // [-0.25, 0.25]; ((A - B) - C) within E, minus F (written as the complement of a union of
  // one, so that a set operation's complement is exercised) = [-1.75, -1.5] u [-0.5, -0.25].
  const Solid a = ball({0, 0, 0}, 2, 1), b = ball({1.5, 0, 0}, 1, 2), c = ball({-1, 0, 0}, 0.5, 3);
  const Solid e = slab_box(-1.75, 0.25, 3, 4), f = ball({0, 0, 0}, 0.25, 5);
  const Solid a_minus_b = csg(SolidKind::kIntersection, {a, inverted(b)});
  const Solid minus_c = csg(SolidKind::kIntersection, {a_minus_b, inverted(c)});
  const Solid u =
      csg(SolidKind::kIntersection, {minus_c, e, inverted(csg(SolidKind::kUnion, {f}))});
  const RenderSolid solid(u, Transform(), kReach);
  expect_hit(solid, {-5, 0, 0}, kPlusX, {-1.75, 4, kMinusX}, "entering E");
  expect_hit(solid, {-1.6, 0, 0}, kPlusX, {-1.5, 3, kPlusX}, "from inside, leaving into C");
  expect_hit(solid, {-1, 0, 0}, kPlusX, {-0.5, 3, kMinusX}, "from inside C");
  expect_hit(solid, {-0.4, 0, 0}, kPlusX, {-0.25, 5, kPlusX}, "leaving into F");
  EXPECT_FALSE(solid.first_hit({0, 0, 0}, kPlusX, 0)) << "from inside F, nothing ahead";
  expect_hit(solid, {5, 0, 0}, kMinusX, {-0.25, 5, kPlusX}, "from beyond, through B and F");
  expect_hit(solid, {-1.55, 0, 0}, kMinusX, {-1.75, 4, kMinusX}, "leaving through E");
  for (double x : {-1.6, -0.3})
    EXPECT_TRUE(solid.contains({x, 0, 0})) << x;
  for (double x : {-1.8, -1.0, 0.0, 1.0})
    EXPECT_FALSE(solid.contains({x, 0, 0})) << x;
}

TEST(SolidCsgCases, RaysStartingInsideAUnionLeaveItsOuterSurface) {
  const RenderSolid solid(csg(SolidKind::kUnion, {ball({0, 0, 0}, 1, 1), ball({1, 0, 0}, 1, 2)}),
                          Transform(), kReach);
  expect_hit(solid, {0.5, 0, 0}, kPlusX, {2, 2, kPlusX}, "towards +x");
  expect_hit(solid, {0.5, 0, 0}, kMinusX, {-1, 1, kMinusX}, "towards -x");
}

// Every solid kind in one tree, for the properties that must hold on any ray.
Solid everything() {
  Solid cone = primitive(SolidKind::kCone,
                         Transform::translate({-1, 0.5, -1}) * Transform::scale({0.7, 0.7, 2}), 3);
  cone.radius0 = 1, cone.radius1 = 0.3;
  Solid torus =
      primitive(SolidKind::kTorus,
                Transform::translate({1, -0.5, 0.2}) * Transform::rotate({0.3, 0, 0, 1}), 4);
  torus.radius1 = 0.35;
  Solid disc = primitive(SolidKind::kDisc,
                         Transform::translate({0, 0, -1.5}) * Transform::scale({2.5, 2.5, 2.5}), 5);
  disc.radius1 = 0.2;
  Solid quadric = primitive(SolidKind::kPolynomial, Transform(), 6);  // x^2 + z^2 <= 0.36
  quadric.polynomial = {{1, 2, 0, 0}, {1, 0, 0, 2}, {-0.36, 0, 0, 0}};
  const Solid cylinder = primitive(
      SolidKind::kCylinder, Transform::translate({0, -2, 0}) * Transform::scale({1, 1, 4}), 7);
  const Solid carved = csg(
      SolidKind::kIntersection,
      {csg(SolidKind::kUnion, {slab_box(-2, 2, 1.5, 1), torus}), inverted(ball({0, 0, 0}, 1.2, 2)),
       inverted(csg(SolidKind::kIntersection, {quadric, slab_box(-3, 3, 3, 8)}))});
  return csg(SolidKind::kUnion, {carved, cone, csg(SolidKind::kIntersection, {disc, cylinder})});
}

TEST(SolidCsgCases, ACutWindowGivesTheUncutHit) {
  // Embree asks with its tfar; the renderer asks again uncut for the hit record: both must agree
  // to the bit before the cut, and the cut must hide what lies at or past it.
  const RenderSolid solid(everything(), Transform(), kReach);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, hidden = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3d o{6 * u(rng), 6 * u(rng), 6 * u(rng)};
    const Vec3d d = normalize(Vec3d{2 * u(rng), 2 * u(rng), 2 * u(rng)} - o);
    const auto uncut = solid.first_hit(o, d, 0);
    if (!uncut) {
      EXPECT_FALSE(solid.first_hit(o, d, 0, 5 + 10 * u(rng)));
      continue;
    }
    ++hits;
    const double t_max = uncut->t * (1 + 0.5 * u(rng));
    const auto cut = solid.first_hit(o, d, 0, t_max);
    if (uncut->t < t_max) {
      ASSERT_TRUE(cut) << i;
      EXPECT_EQ(cut->t, uncut->t) << i;
      EXPECT_EQ(cut->material, uncut->material) << i;
      EXPECT_EQ(cut->normal.x, uncut->normal.x) << i;
      EXPECT_EQ(cut->normal.y, uncut->normal.y) << i;
      EXPECT_EQ(cut->normal.z, uncut->normal.z) << i;
    } else {
      EXPECT_FALSE(cut) << i;
      ++hidden;
    }
    EXPECT_FALSE(solid.first_hit(o, d, 0, uncut->t)) << i;  // the open window ends before it
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(hidden, 300);
}

TEST(SolidCsgCases, AUnionPastTheStackBufferFindsTheNearestBall) {
  // 300 disjoint balls on a grid need more spans than the stack holds (a union's spans are its
  // children's): the per-thread buffer takes them, and the hit is the nearest ball's entry.
  std::vector<Solid> balls;
  std::vector<Vec3d> centres;
  for (int i = 0; i < 300; ++i) {
    centres.push_back({double(i % 10) * 3, double(i / 10 % 10) * 3, double(i / 100) * 3});
    balls.push_back(ball(centres.back(), 1, uint32_t(i)));
  }
  const RenderSolid solid(csg(SolidKind::kUnion, balls), Transform(), kReach);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3d o{-5, 30 * u(rng) - 2, 9 * u(rng) - 2};
    const Vec3d d = normalize(Vec3d{30, 30 * u(rng) - 2, 9 * u(rng) - 2} - o);
    double nearest = HUGE_VAL;
    for (const Vec3d& c : centres) {  // |o + t d - c| = 1, d unit
      const double b = dot(o - c, d), disc = b * b - (dot(o - c, o - c) - 1);
      if (disc > 0) nearest = std::min(nearest, -b - std::sqrt(disc));
    }
    const auto hit = solid.first_hit(o, d, 0);
    ASSERT_EQ(bool(hit), nearest < HUGE_VAL) << i;
    if (!hit) continue;
    ++hits;
    EXPECT_NEAR(hit->t, nearest, 1e-12 * nearest) << i;
  }
  EXPECT_GT(hits, 100);
}

TEST(SolidCsgCases, ATreeBeyondTheIntersectorsBufferIsRefusedAtLoad) {
  // A chain of unions, each adding a ball to the last: the scratch each level keeps grows with
  // its depth, past 2^20 spans at about a thousand levels.
  Solid chain = ball({0, 0, 0}, 1, 0);
  for (int i = 1; i < 1200; ++i) {
    Solid next = csg(SolidKind::kUnion, {ball({double(i), 0, 0}, 1, 0)});
    next.children.insert(next.children.begin(), std::move(chain));  // no copy of the chain
    chain = std::move(next);
  }
  chain.name = "hostile.pov:3:1";
  try {
    RenderSolid solid(chain, Transform(), kReach);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("hostile.pov:3:1"), std::string::npos) << message;
    EXPECT_NE(message.find("1048576"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace fb
