// Exact solids against closed forms: each primitive's hits and normals, transforms, CSG set
// operations, and re-tracing from hits without meeting the same surface again.
#include "core/accel/solid_intersect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <filmback/geometry.h>

#include "core/math/polynomial.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::ball;
using test::csg;
using test::inverted;
using test::kReach;
using test::primitive;

std::optional<SolidHit> trace(const Solid& solid, Vec3d o, Vec3d d, double t_min = 0) {
  return RenderSolid(solid, Transform(), kReach).first_hit(o, d, t_min);
}

void expect_unit_near(Vec3d actual, Vec3d expected, double tolerance) {
  EXPECT_NEAR(length(actual), 1.0, 1e-12);
  EXPECT_LT(length(actual - normalize(expected)), tolerance)
      << actual.x << " " << actual.y << " " << actual.z;
}

// ---- Polynomials --------------------------------------------------------------------------------

TEST(Polynomial, QuarticRootsOfKnownFactorsToFullPrecision) {
  // (t - 1)(t - 2)(t - 3)(t - 10) = t^4 - 16 t^3 + 71 t^2 - 116 t + 60
  const double c[5] = {60, -116, 71, -16, 1};
  double roots[4];
  ASSERT_EQ(sign_changes(c, 4, -100, 100, roots), 4);
  const double expected[4] = {1, 2, 3, 10};
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(roots[i], expected[i], 1e-14 * expected[i]);
  ASSERT_EQ(sign_changes(c, 4, 2.5, 100, roots), 2);  // only those inside the interval
  EXPECT_NEAR(roots[0], 3, 1e-14);
}

TEST(Polynomial, DoubleRootIsNoSignChange) {
  const double c[3] = {1, -2, 1};  // (t - 1)^2
  double roots[2];
  EXPECT_EQ(sign_changes(c, 2, -10, 10, roots), 0);
}

// ---- Primitives -------------------------------------------------------------------------------

TEST(SolidIntersect, SphereHitMissTangentAndInside) {
  const Vec3d c{1, 2, -3};
  const double r = 0.5;
  const Solid s =
      primitive(SolidKind::kSphere, Transform::translate(c) * Transform::scale({r, r, r}));
  const auto hit = trace(s, {1, 2, 5}, {0, 0, -1});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 8 - r, 1e-13);
  expect_unit_near(hit->normal, {0, 0, 1}, 1e-12);
  EXPECT_FALSE(trace(s, {1 + r + 1e-9, 2, 5}, {0, 0, -1}));
  EXPECT_TRUE(trace(s, {1 + r - 1e-9, 2, 5}, {0, 0, -1}));
  const auto inside = trace(s, c, {0, 1, 0});  // from the centre: the exit, normal outward
  ASSERT_TRUE(inside);
  EXPECT_NEAR(inside->t, r, 1e-15);
  expect_unit_near(inside->normal, {0, 1, 0}, 1e-12);
  EXPECT_FALSE(trace(s, {1, 2, 5}, {0, 0, 1}));  // pointing away
}

TEST(SolidIntersect, BoxFacesAndNormals) {
  // corners (0, 0, 0) and (2, 4, 6)
  const Solid s =
      primitive(SolidKind::kBox, Transform::translate({1, 2, 3}) * Transform::scale({1, 2, 3}));
  const auto top = trace(s, {1.5, 10, 1}, {0, -1, 0});
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->t, 6, 1e-14);
  expect_unit_near(top->normal, {0, 1, 0}, 1e-14);
  const auto side = trace(s, {-3, 1, 5}, {1, 0, 0});
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 3, 1e-14);
  expect_unit_near(side->normal, {-1, 0, 0}, 1e-14);
  const auto exit = trace(s, {1, 1, 1}, {0, 0, 1});
  ASSERT_TRUE(exit);
  EXPECT_NEAR(exit->t, 5, 1e-14);
  expect_unit_near(exit->normal, {0, 0, 1}, 1e-14);
  EXPECT_FALSE(trace(s, {3, 1, 1}, {0, 0, 1}));
}

TEST(SolidIntersect, HalfSpaceFromBothSides) {
  // y <= 1: the half-space z <= 0 turned so its normal is +y, raised by 1
  const double q = std::sin(std::numbers::pi / 4);
  const Solid s = primitive(SolidKind::kHalfSpace,
                            Transform::translate({0, 1, 0}) * Transform::rotate({-q, 0, 0, q}));
  const auto above = trace(s, {3, 5, -2}, normalize(Vec3d{0, -1, 1}));
  ASSERT_TRUE(above);
  EXPECT_NEAR(above->t, 4 * std::sqrt(2.0), 1e-13);
  expect_unit_near(above->normal, {0, 1, 0}, 1e-14);
  const auto below = trace(s, {0, -1, 0}, {0, 1, 0});
  ASSERT_TRUE(below);
  EXPECT_NEAR(below->t, 2, 1e-14);
  EXPECT_FALSE(trace(s, {0, 5, 0}, {1, 0, 0}));  // parallel, outside
  EXPECT_FALSE(trace(s, {0, 0, 0}, {1, 0, 0}));  // parallel, inside: no boundary
}

TEST(SolidIntersect, CylinderCapsSideAndOpen) {
  // radius 2, from z = -1 to z = 3
  const Transform place = Transform::translate({0, 0, -1}) * Transform::scale({2, 2, 4});
  Solid s = primitive(SolidKind::kCylinder, place);
  const auto side = trace(s, {10, 0, 1}, {-1, 0, 0});
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 8, 1e-13);
  expect_unit_near(side->normal, {1, 0, 0}, 1e-13);
  const auto cap = trace(s, {0.5, 0.5, 10}, {0, 0, -1});
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->t, 7, 1e-13);
  expect_unit_near(cap->normal, {0, 0, 1}, 1e-13);
  s.open = true;
  EXPECT_FALSE(trace(s, {0.5, 0.5, 10}, {0, 0, -1}));  // in and out through the missing caps
  const auto inner = trace(s, {0, 0, 10}, normalize(Vec3d{1, 0, -4}));  // enters, meets the wall
  ASSERT_TRUE(inner);
  EXPECT_NEAR(inner->position.x, 2, 1e-12);
  expect_unit_near(inner->normal, {1, 0, 0}, 1e-12);  // outward of the set, seen from inside
}

TEST(SolidIntersect, ConeSideMatchesItsSlope) {
  // base radius 2 at z = 0, cap radius 1 at z = 1
  Solid s = primitive(SolidKind::kCone);
  s.radius0 = 2, s.radius1 = 1;
  const double z = 0.25, r = 2 - z;
  const auto hit = trace(s, {-5, 0, z}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5 - r, 1e-13);
  expect_unit_near(hit->normal, {-1, 0, 1}, 1e-13);  // the side leans in by 45 degrees
  const auto apex_side = trace(s, {0, 0, 5}, {0, 0, -1});
  ASSERT_TRUE(apex_side);
  EXPECT_NEAR(apex_side->t, 4, 1e-13);
}

TEST(SolidIntersect, TorusAlongItsPlaneAndThroughTheTube) {
  // major radius 3, minor 1, about z (scaled canonical torus: radius1 is minor / major)
  Solid s = primitive(SolidKind::kTorus, Transform::scale({3, 3, 3}));
  s.radius1 = 1.0 / 3;
  const auto outer = trace(s, {-10, 0, 0}, {1, 0, 0});
  ASSERT_TRUE(outer);
  EXPECT_NEAR(outer->t, 6, 1e-12);
  expect_unit_near(outer->normal, {-1, 0, 0}, 1e-12);
  const auto hole = trace(s, {0, 0, 0}, {1, 0, 0});  // from the centre: the inner equator
  ASSERT_TRUE(hole);
  EXPECT_NEAR(hole->t, 2, 1e-12);
  expect_unit_near(hole->normal, {-1, 0, 0}, 1e-12);
  const auto tube = trace(s, {3, 0, 0}, {0, 0, 1});  // from the tube's core
  ASSERT_TRUE(tube);
  EXPECT_NEAR(tube->t, 1, 1e-12);
  expect_unit_near(tube->normal, {0, 0, 1}, 1e-12);
  // Down -y at x = 3, z = 0.5: the outer wall where the distance from the axis is 3 + sqrt(0.75).
  const auto slanted = trace(s, {3, 10, 0.5}, {0, -1, 0});
  ASSERT_TRUE(slanted);
  const double rho = 3 + std::sqrt(0.75), y = std::sqrt(rho * rho - 9);
  EXPECT_NEAR(slanted->position.y, y, 1e-12);
  expect_unit_near(slanted->normal, {(rho - 3) * 3 / rho, (rho - 3) * y / rho, 0.5}, 1e-12);
  EXPECT_FALSE(trace(s, {0, 0, 5}, {0, 0, -1}));            // down the hole
  EXPECT_FALSE(trace(s, {-10, 0, 1.0 + 1e-9}, {1, 0, 0}));  // just over the top
}

TEST(SolidIntersect, DiscAnnulusOnly) {
  Solid s = primitive(SolidKind::kDisc, Transform::scale({2, 2, 2}));
  s.radius1 = 0.5;  // hole of radius 1
  const auto hit = trace(s, {1.5, 0, 5}, {0, 0, -1});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5, 1e-14);
  expect_unit_near(hit->normal, {0, 0, 1}, 1e-14);
  const auto under = trace(s, {1.5, 0, -5}, {0, 0, 1});
  ASSERT_TRUE(under);
  expect_unit_near(under->normal, {0, 0, 1}, 1e-14);  // the set's outward side, like POV-Ray
  EXPECT_FALSE(trace(s, {0.5, 0, 5}, {0, 0, -1}));    // through the hole
  EXPECT_FALSE(trace(s, {2.5, 0, 5}, {0, 0, -1}));    // beside it
}

// The polynomial solids (POV-Ray's quadric, cubic, quartic, poly), against closed forms.
Solid polynomial(Polynomial3 p, const Transform& world_from_object = Transform()) {
  Solid s = primitive(SolidKind::kPolynomial, world_from_object);
  s.polynomial = std::move(p);
  return s;
}

TEST(Polynomial, RestrictedToARayIsTheSubstitution) {
  // x^2 y z + 3 z^4 - 2 along o + t d, checked at five values of t
  const Polynomial3 p{{1, 2, 1, 1}, {3, 0, 0, 4}, {-2, 0, 0, 0}};
  const Vec3d o{0.5, -1.5, 2}, d{1, 0.25, -0.75};
  double c[kMaxPolynomialDegree + 1];
  restrict_to_ray(p, o, d, c);
  for (double t : {-2.0, -0.5, 0.0, 1.0, 3.0})
    EXPECT_NEAR(evaluate_polynomial(c, 4, t), evaluate_polynomial3(p, o + d * t), 1e-12);
  EXPECT_EQ(polynomial3_degree(p), 4);
  const Vec3d g = polynomial3_gradient(p, o);  // 2xyz, x^2 z, x^2 y + 12 z^3
  EXPECT_NEAR(g.x, 2 * 0.5 * -1.5 * 2, 1e-14);
  EXPECT_NEAR(g.y, 0.25 * 2, 1e-14);
  EXPECT_NEAR(g.z, 0.25 * -1.5 + 12 * 8, 1e-12);
}

TEST(SolidIntersect, QuadricSphereIsTheSphere) {
  // x^2 + y^2 + z^2 - 4 <= 0, and the same as a sphere of radius 2, on random rays
  const Solid q = polynomial({{1, 2, 0, 0}, {1, 0, 2, 0}, {1, 0, 0, 2}, {-4, 0, 0, 0}});
  const Solid sphere = primitive(SolidKind::kSphere, Transform::scale({2, 2, 2}));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    // from anywhere in a box of half-size 5 (inside the sphere too) towards |p| <= 2.5
    const Vec3d o{5 * u(rng), 5 * u(rng), 5 * u(rng)};
    const Vec3d d = normalize(Vec3d{2.5 * u(rng), 2.5 * u(rng), 2.5 * u(rng)} - o);
    const auto a = trace(q, o, d), b = trace(sphere, o, d);
    ASSERT_EQ(bool(a), bool(b));
    if (!a) continue;
    ++hits;
    EXPECT_NEAR(a->t, b->t, 1e-12);
    expect_unit_near(a->normal, b->normal, 1e-12);
  }
  EXPECT_GT(hits, 250);
}

TEST(SolidIntersect, UnboundedQuadricCylinderCutByABox) {
  // x^2 + y^2 - 1 <= 0 runs along z for ever; intersected with the box |p| <= 2 it is a capped
  // cylinder of length 4
  const Solid cylinder = polynomial({{1, 2, 0, 0}, {1, 0, 2, 0}, {-1, 0, 0, 0}});
  const auto side = trace(cylinder, {-5, 0, 1e5}, {1, 0, 0});  // far along z: still there
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 4, 1e-9);
  expect_unit_near(side->normal, {-1, 0, 0}, 1e-12);
  const Solid capped = csg(SolidKind::kIntersection,
                           {cylinder, primitive(SolidKind::kBox, Transform::scale({2, 2, 2}))});
  const auto cap = trace(capped, {0.5, 0, 10}, {0, 0, -1});
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->t, 8, 1e-12);
  expect_unit_near(cap->normal, {0, 0, 1}, 1e-12);
  EXPECT_FALSE(trace(capped, {1.5, 0, 10}, {0, 0, -1}));  // outside the cylinder, inside the box
}

TEST(SolidIntersect, QuarticTorusIsTheTorus) {
  // (x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2), R = 3, r = 1, expanded
  const double R2 = 9, k = R2 - 1;
  const Polynomial3 p{{1, 4, 0, 0},
                      {1, 0, 4, 0},
                      {1, 0, 0, 4},
                      {2, 2, 2, 0},
                      {2, 2, 0, 2},
                      {2, 0, 2, 2},
                      {2 * k - 4 * R2, 2, 0, 0},
                      {2 * k - 4 * R2, 0, 2, 0},
                      {2 * k, 0, 0, 2},
                      {k * k, 0, 0, 0}};
  const Solid quartic = polynomial(p, Transform::translate({0, 0, 1}));
  const auto outer = trace(quartic, {-10, 0, 1}, {1, 0, 0});
  ASSERT_TRUE(outer);
  EXPECT_NEAR(outer->t, 6, 1e-12);
  expect_unit_near(outer->normal, {-1, 0, 0}, 1e-12);
  const auto hole = trace(quartic, {0, 0, 1}, {1, 0, 0});
  ASSERT_TRUE(hole);
  EXPECT_NEAR(hole->t, 2, 1e-12);
  const auto top = trace(quartic, {3, 0, 10}, {0, 0, -1});
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->t, 8, 1e-12);
  expect_unit_near(top->normal, {0, 0, 1}, 1e-12);
  EXPECT_FALSE(trace(quartic, {0, 0, 10}, {0, 0, -1}));  // down the hole
}

// ---- Transforms -------------------------------------------------------------------------------

TEST(SolidIntersect, MirroredNonUniformSphereIsTheEllipsoid) {
  const Vec3d axes{2, 0.5, 3};
  const Solid s = primitive(SolidKind::kSphere, Transform::scale({-axes.x, axes.y, axes.z}));
  EXPECT_NEAR(trace(s, {10, 0, 0}, {-1, 0, 0})->t, 8, 1e-13);
  EXPECT_NEAR(trace(s, {0, -10, 0}, {0, 1, 0})->t, 9.5, 1e-13);
  // At (x, y, 0) on the ellipse the outward normal is (x / a^2, y / b^2, 0).
  const double x = 1;
  const double y = axes.y * std::sqrt(1 - x * x / (axes.x * axes.x));
  const auto hit = trace(s, {x, 10, 0}, {0, -1, 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->position.y, y, 1e-13);
  expect_unit_near(hit->normal, {x / (axes.x * axes.x), y / (axes.y * axes.y), 0}, 1e-12);
}

TEST(SolidIntersect, ShearedBoxNormalIsTheImplicitGradient) {
  // x' = x + 0.5 y: the box's +y face stays horizontal, its +x face leans
  const Transform shear = Transform::from_rows({1, 0.5, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
  const Solid s = primitive(SolidKind::kBox, shear);
  const auto side = trace(s, {10, 0.5, 0}, {-1, 0, 0});
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->position.x, 1.25, 1e-13);
  expect_unit_near(side->normal, {1, -0.5, 0}, 1e-13);  // M^-T (1, 0, 0)
  const auto top = trace(s, {0, 10, 0}, {0, -1, 0});
  expect_unit_near(top->normal, {0, 1, 0}, 1e-13);
}

TEST(SolidIntersect, TinySphereFarAwayKeepsItsPrecision) {
  const double r = 1e-3, distance = 1e4;
  const Solid s = primitive(SolidKind::kSphere, Transform::translate({0.3 * r, 0, -distance}) *
                                                    Transform::scale({r, r, r}));
  const auto hit = trace(s, {0, 0, 0}, {0, 0, -1});
  ASSERT_TRUE(hit);
  const double expected = distance - std::sqrt(r * r - 0.09 * r * r);
  EXPECT_NEAR(hit->t, expected, 1e-15 * distance * 8);
  expect_unit_near(hit->normal, {-0.3, 0, std::sqrt(1 - 0.09)}, 1e-9);
}

// ---- CSG --------------------------------------------------------------------------------------

TEST(SolidCsg, TruthTableAlongALine) {
  // A = [-1, 1] and B = [0.5, 1.5] on the x axis; rays from both ends give both boundaries.
  const Solid a = ball({0, 0, 0}, 1, 1), b = ball({1, 0, 0}, 0.5, 2);
  Solid not_b = b;
  not_b.inverse = true;
  struct Case {
    const char* name;
    Solid solid;
    double from_left, from_right;  // the first boundary's x from each end
    uint32_t left_material, right_material;
  };
  const Case cases[] = {
      {"union", csg(SolidKind::kUnion, {a, b}), -1, 1.5, 1, 2},
      {"intersection", csg(SolidKind::kIntersection, {a, b}), 0.5, 1, 2, 1},
      {"a - b", csg(SolidKind::kIntersection, {a, not_b}), -1, 0.5, 1, 2},
      {"b - a",
       csg(SolidKind::kIntersection, {b,
                                      [&] {
                                        Solid n = a;
                                        n.inverse = true;
                                        return n;
                                      }()}),
       1, 1.5, 1, 2},
  };
  for (const Case& c : cases) {
    const auto left = trace(c.solid, {-5, 0, 0}, {1, 0, 0});
    const auto right = trace(c.solid, {5, 0, 0}, {-1, 0, 0});
    ASSERT_TRUE(left && right) << c.name;
    EXPECT_NEAR(left->position.x, c.from_left, 1e-14) << c.name;
    EXPECT_NEAR(right->position.x, c.from_right, 1e-14) << c.name;
    EXPECT_EQ(left->material, c.left_material) << c.name;
    EXPECT_EQ(right->material, c.right_material) << c.name;
    expect_unit_near(left->normal, {-1, 0, 0}, 1e-14);  // out of the set, towards the ray
    expect_unit_near(right->normal, {1, 0, 0}, 1e-14);
  }
  Solid everything_but = csg(SolidKind::kUnion, {a, b});
  everything_but.inverse = true;
  const auto from_outside = trace(everything_but, {-5, 0, 0}, {1, 0, 0});
  ASSERT_TRUE(from_outside);  // inside the complement: the first boundary enters A
  EXPECT_NEAR(from_outside->position.x, -1, 1e-14);
  expect_unit_near(from_outside->normal, {1, 0, 0}, 1e-14);
}

TEST(SolidCsg, RayThroughTheBiteTakesTheCutSurface) {
  const Solid a = ball({0, 0, 0}, 1, 1);
  Solid bite = ball({1, 0, 0}, 0.5, 2);
  bite.inverse = true;
  const Solid difference = csg(SolidKind::kIntersection, {a, bite});
  // Down the y axis at x = 0.8: A spans |y| <= 0.6, the bite |y| <= sqrt(0.21).
  const auto first = trace(difference, {0.8, 5, 0}, {0, -1, 0});
  ASSERT_TRUE(first);
  EXPECT_NEAR(first->position.y, 0.6, 1e-14);
  EXPECT_EQ(first->material, 1u);
  expect_unit_near(first->normal, {0.8, 0.6, 0}, 1e-13);
  const auto cut = trace(difference, {0.8, 0.59, 0}, {0, -1, 0});  // from inside the solid
  ASSERT_TRUE(cut);
  const double y = std::sqrt(0.21);
  EXPECT_NEAR(cut->position.y, y, 1e-14);
  EXPECT_EQ(cut->material, 2u);  // POV-Ray: the cut surface wears the subtracted object's texture
  // Outward of A - B there is into the bite: towards its centre (1, 0, 0).
  expect_unit_near(cut->normal, Vec3d{1, 0, 0} - Vec3d{0.8, y, 0}, 1e-13);
  const auto across = trace(difference, {0.8, 0, 0}, {0, -1, 0});  // in the bite, not the solid
  ASSERT_TRUE(across);
  EXPECT_NEAR(across->position.y, -y, 1e-14);
  expect_unit_near(across->normal, Vec3d{1, 0, 0} - Vec3d{0.8, -y, 0}, 1e-13);
  EXPECT_FALSE(trace(difference, {0.9, 0, 5}, {0, 0, -1}));  // the bite removes this whole chord
}

TEST(SolidCsg, HalfSpaceClipsASphereAndIsBoundedByIt) {
  const Solid cap = csg(SolidKind::kIntersection,
                        {ball({0, 0, 0}, 1, 1), primitive(SolidKind::kHalfSpace, Transform(), 3)});
  const RenderSolid solid(cap, Transform(), kReach);
  EXPECT_TRUE(solid.bounded());
  EXPECT_NEAR(solid.bounds().hi.z, 1, 1e-15);
  const auto top = solid.first_hit({0.5, 0, 5}, {0, 0, -1}, 0);
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->position.z, 0, 1e-15);
  EXPECT_EQ(top->material, 3u);
  EXPECT_FALSE(solid.first_hit({0.5, 0, 5}, {0, 1, 0}, 0));
}

TEST(SolidCsg, ClippingLeavesTheObjectOpen) {
  // A unit sphere clipped_by z <= 0: a bowl, open at the top, seen from above through its rim.
  Solid clip = primitive(SolidKind::kHalfSpace, Transform(), 3);
  clip.bounds_only = true;
  const Solid bowl = csg(SolidKind::kIntersection, {ball({0, 0, 0}, 1, 1), clip});
  const auto inner = trace(bowl, {0, 0, 5}, {0, 0, -1});
  ASSERT_TRUE(inner);
  EXPECT_NEAR(inner->position.z, -1, 1e-14);  // the bowl's bottom, from inside
  EXPECT_EQ(inner->material, 1u);
  expect_unit_near(inner->normal, {0, 0, -1}, 1e-14);  // still the sphere's outward normal
  EXPECT_FALSE(trace(bowl, {0, 0, 0.5}, {1, 0, 0}));   // above the cut: nothing left
}

// ---- Re-tracing from hits -----------------------------------------------------------------------

// From every hit, rays leaving on either side must not meet the surface they leave: offset by
// the hit's error bound (pbrt's offset_ray_origin, as the integrators do) and traced in float
// like a render, the next hit is not the point left (at t ~ its error, below 1e-6 of the size)
// but a genuine one (chords this short are vanishingly rare).
TEST(SolidIntersect, NoSelfIntersectionAtAnyScale) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto random_unit = [&] {
    for (;;) {
      const Vec3d v{u(rng), u(rng), u(rng)};
      if (dot(v, v) > 1e-3 && dot(v, v) <= 1) return normalize(v);
    }
  };
  for (double scale : {1e-3, 1e-1, 1.0, 1e2, 1e4}) {
    std::vector<Solid> solids;
    const Transform place = Transform::translate({scale * 3, scale * 0.5, -scale * 4}) *
                            Transform::rotate({0.2, 0.3, 0.1, 0.9}) *
                            Transform::scale({scale, scale * 0.7, scale * 1.3});
    for (SolidKind kind : {SolidKind::kSphere, SolidKind::kBox, SolidKind::kCylinder,
                           SolidKind::kCone, SolidKind::kTorus}) {
      Solid s = primitive(kind, place);
      s.radius0 = 1, s.radius1 = kind == SolidKind::kTorus ? 0.3 : 0.4;
      solids.push_back(s);
    }
    Solid bite = ball(place.point({0.8, 0, 0}), 0.6 * scale, 2);
    bite.inverse = true;
    solids.push_back(csg(SolidKind::kIntersection, {ball(place.point({}), scale, 1), bite}));
    for (const Solid& s : solids) {
      const RenderSolid solid(s, Transform(), kReach);
      int hits = 0;
      for (int i = 0; i < 400; ++i) {
        const Vec3f o(Vec3d{0, 0, 0});
        const Vec3f d(normalize(place.point({}) + random_unit() * (1.5 * scale)));
        const auto hit = solid.first_hit(Vec3d(o), Vec3d(d), 0);
        if (!hit) continue;
        ++hits;
        const Vec3f n(hit->normal), p(hit->position), error(hit->position_error);
        for (int side : {1, -1}) {
          Vec3f w(random_unit());
          if (dot(w, n) * side < 0) w = -w;
          if (std::abs(dot(w, n)) < 0.1f) continue;
          const Vec3f from = offset_ray_origin(p, error, n, w);
          const auto next = solid.first_hit(Vec3d(from), Vec3d(w), 0);
          if (next) {
            ASSERT_GT(next->t, 1e-5 * scale) << "scale " << scale << " side " << side;
          }
        }
      }
      EXPECT_GT(hits, 50) << scale;
    }
  }
}

}  // namespace
}  // namespace fb
