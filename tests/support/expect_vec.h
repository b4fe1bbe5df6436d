// Vectors compared component by component in GoogleTest, within a tolerance the caller names.
#pragma once

#include <gtest/gtest.h>

#include <filmback/vec.h>

namespace fb::test {

inline void expect_vec_near(Vec3d actual, Vec3d expected, double tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// Posed vertices against their closed form (issue 21: within 1e-6), the vertex data being single
// precision.
constexpr double kVertexTolerance = 1e-6;

inline void expect_vertex_near(Vec3f actual, Vec3d expected) {
  expect_vec_near(Vec3d(actual), expected, kVertexTolerance);
}

}  // namespace fb::test
