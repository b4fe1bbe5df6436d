#include "core/scene/animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/math/constants.h"

namespace fb {
namespace {

AnimationCurve curve(TrsPath path, Interpolation interpolation, std::vector<double> times,
                     std::vector<double> values) {
  AnimationCurve c;
  c.node = 0;
  c.path = path;
  c.interpolation = interpolation;
  c.times_s = std::move(times);
  c.values = std::move(values);
  return c;
}

std::array<double, 4> at(const AnimationCurve& c, double t) {
  std::array<double, 4> v{};
  c.evaluate(t, v.data());
  return v;
}

Quatd about_z(double angle) {
  return {0, 0, std::sin(angle / 2), std::cos(angle / 2)};
}

TEST(AnimationCurve, LinearInterpolatesBetweenKeysAndClampsOutside) {
  const AnimationCurve c =
      curve(TrsPath::kTranslation, Interpolation::kLinear, {1, 3, 4}, {0, 0, 0, 4, 2, -2, 4, 2, 6});
  EXPECT_EQ(at(c, 1.5), (std::array<double, 4>{1, 0.5, -0.5, 0}));
  EXPECT_EQ(at(c, 3.25), (std::array<double, 4>{4, 2, 0, 0}));
  EXPECT_EQ(at(c, -7), (std::array<double, 4>{0, 0, 0, 0}));  // before the first key: its value
  EXPECT_EQ(at(c, 9), (std::array<double, 4>{4, 2, 6, 0}));   // after the last: its value
  EXPECT_EQ(at(c, 3), (std::array<double, 4>{4, 2, -2, 0}));  // on a key: exactly its value
}

TEST(AnimationCurve, StepHoldsEachKeyUntilTheNext) {
  const AnimationCurve c =
      curve(TrsPath::kScale, Interpolation::kStep, {0, 1, 2}, {1, 1, 1, 2, 2, 2, 5, 6, 7});
  EXPECT_EQ(at(c, 0.999)[0], 1);
  EXPECT_EQ(at(c, 1.0)[0], 2);
  EXPECT_EQ(at(c, 1.999)[1], 2);
  EXPECT_EQ(at(c, 2.0)[2], 7);
  EXPECT_EQ(at(c, 30)[2], 7);
}

// glTF 2.0 Appendix C's Hermite spline, worked by hand at s = 1/4 of a segment of length 2:
// h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875, so with v0 = 1, b0 = 0.5,
// v1 = 3, a1 = -1: p = 0.84375 + 2 (0.140625)(0.5) + 0.15625 (3) + 2 (-0.046875)(-1) = 1.546875.
TEST(AnimationCurve, CubicSplineFollowsTheHermiteFormula) {
  // Per key: in-tangent, value, out-tangent (x carries the worked example, y and z zeros).
  const AnimationCurve c = curve(TrsPath::kTranslation, Interpolation::kCubicSpline, {1, 3},
                                 {9, 0, 0, 1, 0, 0, 0.5, 0, 0,  //
                                  -1, 0, 0, 3, 0, 0, 9, 0, 0});
  EXPECT_DOUBLE_EQ(at(c, 1.5)[0], 1.546875);
  EXPECT_EQ(at(c, 1)[0], 1);  // keys are met exactly; tangents outside the keys do not count
  EXPECT_EQ(at(c, 3)[0], 3);
  EXPECT_EQ(at(c, 0)[0], 1);
  EXPECT_EQ(at(c, 4)[0], 3);
}

TEST(Slerp, TurnsAtConstantAngularSpeedAlongTheShorterArc) {
  const Quatd a = about_z(0), b = about_z(kPi / 2);
  for (double t : {0.0, 1.0 / 3, 0.5, 0.9, 1.0}) {
    const Quatd q = slerp(a, b, t), expected = about_z(t * kPi / 2);
    EXPECT_NEAR(q.z, expected.z, 1e-15) << t;
    EXPECT_NEAR(q.w, expected.w, 1e-15) << t;
  }
  // -b is the same rotation: the result is the same rotation (q up to sign).
  const Quatd q = slerp(a, {-b.x, -b.y, -b.z, -b.w}, 1.0 / 3), expected = about_z(kPi / 6);
  EXPECT_NEAR(std::abs(q.z * expected.z + q.w * expected.w), 1.0, 1e-15);
  // A turn of 200 degrees is reached by turning -160 degrees.
  const Quatd r = slerp(a, about_z(200 * kPi / 180), 0.5), half = about_z(-80 * kPi / 180);
  EXPECT_NEAR(std::abs(r.z * half.z + r.w * half.w), 1.0, 1e-15);
}

TEST(Slerp, NearlyEqualRotationsStayFiniteAndUnit) {
  const Quatd a = about_z(1.0), b = about_z(1.0 + 1e-13);
  const Quatd q = slerp(a, b, 0.5);
  EXPECT_NEAR(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, 1.0, 1e-15);
  EXPECT_NEAR(q.z, about_z(1.0 + 5e-14).z, 1e-15);
}

TEST(AnimationCurve, LinearRotationsSlerpAndCubicOnesAreNormalised) {
  const Quatd a = about_z(0.2), b = about_z(1.4);
  const AnimationCurve linear = curve(TrsPath::kRotation, Interpolation::kLinear, {0, 2},
                                      {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w});
  const std::array<double, 4> q = at(linear, 0.5);
  EXPECT_NEAR(q[2], about_z(0.5).z, 1e-15);
  EXPECT_NEAR(q[3], about_z(0.5).w, 1e-15);
  // Zero tangents between two rotations: the Hermite blend of the quaternions, renormalised.
  const AnimationCurve cubic = curve(
      TrsPath::kRotation, Interpolation::kCubicSpline, {0, 2},
      {0, 0, 0, 0, a.x, a.y, a.z, a.w, 0, 0, 0, 0, 0, 0, 0, 0, b.x, b.y, b.z, b.w, 0, 0, 0, 0});
  const std::array<double, 4> c = at(cubic, 1.0);  // s = 1/2: equal weights of a and b
  const double n = std::hypot(a.z + b.z, a.w + b.w);
  EXPECT_NEAR(c[2], (a.z + b.z) / n, 1e-15);
  EXPECT_NEAR(c[3], (a.w + b.w) / n, 1e-15);
}

TEST(AnimationCurve, VariesOnlyWhereItsValueCanChange) {
  const AnimationCurve c = curve(TrsPath::kTranslation, Interpolation::kLinear, {0, 1, 2, 3},
                                 {0, 0, 0, 1, 0, 0, 1, 0, 0, 5, 0, 0});
  EXPECT_TRUE(c.varies(0.2, 0.3));
  EXPECT_FALSE(c.varies(1.1, 1.9));  // between two equal keys
  EXPECT_FALSE(c.varies(1.0, 2.0));  // exactly from one equal key to the next
  EXPECT_TRUE(c.varies(1.9, 2.1));   // into the last segment
  EXPECT_FALSE(c.varies(-5, 0));     // before the first key
  EXPECT_FALSE(c.varies(3, 9));      // after the last
  EXPECT_FALSE(c.varies(0.5, 0.5));  // an instant
  const AnimationCurve step =
      curve(TrsPath::kTranslation, Interpolation::kStep, {0, 1}, {0, 0, 0, 1, 0, 0});
  EXPECT_FALSE(step.varies(0.2, 0.9));
  EXPECT_TRUE(step.varies(0.9, 1.0));  // the jump at 1 is inside [0.9, 1]
  // Equal values, but a tangent bends the spline between them.
  const AnimationCurve bent = curve(TrsPath::kTranslation, Interpolation::kCubicSpline, {0, 1},
                                    {0, 0, 0, 2, 0, 0, 0, 1, 0,  //
                                     0, 0, 0, 2, 0, 0, 0, 0, 0});
  EXPECT_TRUE(bent.varies(0.4, 0.6));
  AnimationCurve flat = bent;
  flat.values[7] = 0;
  EXPECT_FALSE(flat.varies(0.4, 0.6));
}

// A parent turning about +Y at 1 rad/s carries a child 2 m out along +X; a sibling stays put.
TEST(NodeHierarchy, ChildrenFollowTheirAnimatedParents) {
  NodeHierarchy h;
  const uint32_t root =
      h.add_node(kNoNode, Transform::translate({0, 0, -5}), {{0, 0, -5}, {}, {1, 1, 1}});
  Trs arm;
  arm.translation = {2, 0, 0};
  const uint32_t child = h.add_node(root, arm.matrix(), arm);
  const uint32_t still =
      h.add_node(kNoNode, Transform::translate({7, 0, 0}), {{7, 0, 0}, {}, {1, 1, 1}});
  AnimationCurve turn = curve(TrsPath::kRotation, Interpolation::kLinear, {0, 1},
                              {0, 0, 0, 1, 0, std::sin(0.5), 0, std::cos(0.5)});
  turn.node = root;
  h.curves.push_back(turn);
  h.finish();
  for (double t : {0.0, 0.25, 0.7, 1.0}) {
    const Vec3d p = h.world_from_node(child, t).point({0, 0, 0});
    // Rotation by t about +Y takes +X to (cos t, 0, -sin t).
    EXPECT_NEAR(p.x, 2 * std::cos(t), 1e-12) << t;
    EXPECT_NEAR(p.y, 0, 1e-12) << t;
    EXPECT_NEAR(p.z, -5 - 2 * std::sin(t), 1e-12) << t;
  }
  EXPECT_TRUE(h.moves(child, 0.1, 0.2));
  EXPECT_FALSE(h.moves(child, 1.5, 2.0));  // after the last key
  EXPECT_FALSE(h.moves(still, 0.1, 0.2));
  EXPECT_EQ(h.world_from_node(still, 0.3).point({0, 0, 0}).x, 7);
}

}  // namespace
}  // namespace fb
