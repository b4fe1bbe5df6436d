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

}  // namespace fb::test
