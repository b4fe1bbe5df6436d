// The footprint's geometry against closed forms: a pinhole's neighbouring rays on a plane, the
// spread approximation on a plane seen head-on and obliquely, and texture coordinate derivatives
// carried through a triangle's corners.
#include "core/texture/ray_footprint.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fb {
namespace {

constexpr float kTolerance = 1e-5f;

void expect_near(Vec3f a, Vec3f b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

// A pinhole at the origin with focal length f px: the ray through raster offset (x, y) from the
// centre points along (x / f, y / f, -1). Its neighbours meet the plane z = -d at offsets d / f
// along x and y, whatever point of the plane the ray itself hits.
TEST(RayFootprint, PinholeDifferentialsOnAPlaneFacingTheCamera) {
  const float f = 500.f, d = 7.f;
  const Vec3f direction{0.2f, -0.1f, -1.f};
  RayDifferential differential;
  differential.dx_direction = {1.f / f, 0.f, 0.f};
  differential.dy_direction = {0.f, 1.f / f, 0.f};
  FootprintSource source;
  source.differential = &differential;
  Vec3f dp_dx, dp_dy;
  ASSERT_TRUE(
      position_differentials(source, {}, direction, direction * d, {0.f, 0.f, 1.f}, dp_dx, dp_dy));
  expect_near(dp_dx, {d / f, 0.f, 0.f}, kTolerance);
  expect_near(dp_dy, {0.f, d / f, 0.f}, kTolerance);
  // Supersampling narrows it: 16 samples a pixel, a quarter.
  source.scale = footprint_scale(16);
  ASSERT_TRUE(
      position_differentials(source, {}, direction, direction * d, {0.f, 0.f, 1.f}, dp_dx, dp_dy));
  expect_near(dp_dx, {d / f / 4.f, 0.f, 0.f}, kTolerance);
}

TEST(RayFootprint, ScaleFollowsPbrtsSupersamplingRule) {
  EXPECT_FLOAT_EQ(footprint_scale(1), 1.f);
  EXPECT_FLOAT_EQ(footprint_scale(4), 0.5f);
  EXPECT_FLOAT_EQ(footprint_scale(64), 0.125f);
  EXPECT_FLOAT_EQ(footprint_scale(1024), 0.125f);  // never below 1/8
}

// Without a differential, the spread: a plane at distance d seen head-on gets a footprint of
// origin + angle * d across; tilted by theta about the beam, it stretches by 1 / cos(theta) along
// the tilt, and its area by the same.
TEST(RayFootprint, SpreadGrowsWithDistanceAndStretchesObliquely) {
  FootprintSource source;
  source.spread = {0.01f, 0.002f};
  const Vec3f position{0.f, 0.f, -10.f};
  Vec3f dp_dx, dp_dy;
  ASSERT_TRUE(position_differentials(source, {3.f, 4.f, 5.f}, {0.f, 1.f, 0.f}, position,
                                     {0.f, 0.f, 1.f}, dp_dx, dp_dy));
  const float width = 0.01f + 0.002f * 10.f;
  EXPECT_NEAR(length(dp_dx), width, kTolerance);
  EXPECT_NEAR(length(dp_dy), width, kTolerance);
  EXPECT_NEAR(dot(dp_dx, dp_dy), 0.f, kTolerance);
  const float theta = 1.2f;  // rad
  const Vec3f tilted{0.f, std::sin(theta), std::cos(theta)};
  ASSERT_TRUE(position_differentials(source, {}, {}, position, tilted, dp_dx, dp_dy));
  EXPECT_NEAR(length(cross(dp_dx, dp_dy)), width * width / std::cos(theta), 1e-6f);
  EXPECT_NEAR(dot(dp_dx, tilted), 0.f, kTolerance);  // on the tangent plane
  EXPECT_NEAR(dot(dp_dy, tilted), 0.f, kTolerance);
}

TEST(RayFootprint, NoSourceOrAParallelPlaneGivesNoFootprint) {
  Vec3f dp_dx, dp_dy;
  EXPECT_FALSE(position_differentials({}, {}, {0.f, 0.f, -1.f}, {0.f, 0.f, -2.f}, {0.f, 0.f, 1.f},
                                      dp_dx, dp_dy));
  RayDifferential differential;
  differential.dx_direction = {0.01f, 0.f, 0.f};
  FootprintSource source;
  source.differential = &differential;
  // The plane contains the ray: its y neighbour (no offset) runs parallel to it, and there is no
  // spread to fall back on.
  EXPECT_FALSE(position_differentials(source, {}, {0.f, 0.f, -1.f}, {0.f, 0.f, -2.f},
                                      {1.f, 0.f, 0.f}, dp_dx, dp_dy));
}

// A right triangle in the z = 0 plane, 2 m by 4 m, textured (u, v) = (x / 2, y / 4) in set 0 and
// (v, u) in set 1: dp/dx = (0.1, 0.2, 0) moves set 0 by (0.05, 0.05) and set 1 by (0.05, 0.05);
// dp/dy = (0, 1, 0) moves them by (0, 0.25) and (0.25, 0).
TEST(RayFootprint, TextureDerivativesFollowTheCornersCoordinates) {
  const Vec3f p[3] = {{1.f, 1.f, 0.f}, {3.f, 1.f, 0.f}, {1.f, 5.f, 0.f}};
  const uint32_t corner[3] = {2, 0, 1};  // vertex indices, not in order
  VertexTextureData data;
  data.texcoords[0] = {{1.5f, 0.25f}, {0.5f, 1.25f}, {0.5f, 0.25f}};
  for (const Vec2f uv : data.texcoords[0])
    data.texcoords[1].push_back({uv.y, uv.x});
  SurfacePoint point;
  point.uv_sets = 2;
  set_texture_differentials(p, corner, data, {0.1f, 0.2f, 0.f}, {0.f, 1.f, 0.f}, point);
  EXPECT_NEAR(point.duv_dx[0].x, 0.05f, kTolerance);
  EXPECT_NEAR(point.duv_dx[0].y, 0.05f, kTolerance);
  EXPECT_NEAR(point.duv_dy[0].x, 0.f, kTolerance);
  EXPECT_NEAR(point.duv_dy[0].y, 0.25f, kTolerance);
  EXPECT_NEAR(point.duv_dy[1].x, 0.25f, kTolerance);
  EXPECT_NEAR(point.duv_dy[1].y, 0.f, kTolerance);
  // Through a texture transform (s, t) = (2u + 0.5, 3v): the linear part only.
  const TexturePosition at = texture_position(point, 0, {2.f, 0.f, 0.5f, 0.f, 3.f, 0.f});
  EXPECT_NEAR(at.dst_dx.x, 0.1f, kTolerance);
  EXPECT_NEAR(at.dst_dy.y, 0.75f, kTolerance);
}

TEST(RayFootprint, DegenerateTriangleLeavesNoDerivatives) {
  const Vec3f p[3] = {{0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}, {2.f, 2.f, 2.f}};
  const uint32_t corner[3] = {0, 1, 2};
  VertexTextureData data;
  data.texcoords[0] = {{0.f, 0.f}, {1.f, 0.f}, {0.f, 1.f}};
  SurfacePoint point;
  point.uv_sets = 1;
  set_texture_differentials(p, corner, data, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, point);
  EXPECT_EQ(point.duv_dx[0].x, 0.f);
  EXPECT_EQ(point.duv_dy[0].y, 0.f);
}

}  // namespace
}  // namespace fb
