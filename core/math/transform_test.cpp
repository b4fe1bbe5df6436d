#include "core/math/transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/expect_vec.h"

namespace fb {
namespace {

using test::expect_vec_near;

TEST(Transform, QuaternionRotatesAboutItsAxis) {
  const double half = std::numbers::pi / 4;  // 90 degrees about +Y
  const Transform r = Transform::rotate({0, std::sin(half), 0, std::cos(half)});
  expect_vec_near(r.vector({1, 0, 0}), {0, 0, -1}, 1e-15);  // right-handed: +X turns to -Z
  expect_vec_near(r.vector({0, 1, 0}), {0, 1, 0}, 1e-15);
}

TEST(Transform, GltfColumnMajorMatrixMatchesTrs) {
  const Transform trs = Transform::translate({1, 2, 3}) * Transform::rotate({0.1, 0.2, 0.3, 0.9}) *
                        Transform::scale({2, 3, 4});
  std::array<double, 16> columns;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      columns[c * 4 + r] = trs(r, c);
  const Transform m = Transform::from_columns(columns);
  expect_vec_near(m.point({0.5, -1, 2}), trs.point({0.5, -1, 2}), 1e-14);
  expect_vec_near(m.translation(), {1, 2, 3}, 0);
}

TEST(Transform, InverseUndoesAffineMaps) {
  const Transform t = Transform::translate({1e5, -3, 7}) *
                      Transform::rotate({0.3, -0.2, 0.1, 0.9}) * Transform::scale({0.5, 2, 3});
  const Vec3d p{12.25, -0.5, 1e-3};
  expect_vec_near(t.inverse().point(t.point(p)), p, 1e-10);
  expect_vec_near((t.inverse() * t).point({1, 1, 1}), {1, 1, 1}, 1e-12);
}

TEST(Transform, SingularMatrixInverseIsNotFinite) {
  EXPECT_FALSE(Transform::scale({1, 0, 1}).inverse().is_finite());
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
  const Transform t = Transform::rotate({0.2, 0.4, 0.1, 0.8}) * Transform::scale({1, 5, 0.25});
  const Vec3d tangent{1, -1, 0}, normal{1, 1, 0};  // perpendicular in object space
  const Vec3d n = t.normal_transform().vector(normal);
  EXPECT_NEAR(dot(n, t.vector(tangent)), 0.0, 1e-12);
}

TEST(Transform, LookAtLooksDownMinusZWithYUp) {
  const Transform camera = Transform::look_at({0, 0, 10}, {0, 0, 0}, {0, 1, 0});
  expect_vec_near(camera.vector({0, 0, -1}), {0, 0, -1}, 1e-15);
  expect_vec_near(camera.vector({0, 1, 0}), {0, 1, 0}, 1e-15);
  expect_vec_near(camera.point({0, 0, 0}), {0, 0, 10}, 0);
}

TEST(Transform, WithoutScaleKeepsTheRotation) {
  const Transform r = Transform::rotate({0.1, 0.7, -0.2, 0.6});
  const Transform scaled = Transform::translate({4, 5, 6}) * r * Transform::scale({3, 3, 0.1});
  const Transform stripped = scaled.without_scale_and_translation();
  expect_vec_near(stripped.vector({0.3, -0.4, 0.5}), r.vector({0.3, -0.4, 0.5}), 1e-14);
  expect_vec_near(stripped.translation(), {0, 0, 0}, 0);
  EXPECT_NEAR(stripped.determinant3x3(), 1.0, 1e-14);
  EXPECT_LT(Transform::scale({-1, 1, 1}).determinant3x3(), 0.0);
}

}  // namespace
}  // namespace fb
