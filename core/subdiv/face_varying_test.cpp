// A UV map's corners joined into face-varying values as Blender's subdivision converter joins them
// (core/subdiv/face_varying.h): what makes a seam.
#include "core/subdiv/face_varying.h"

#include <gtest/gtest.h>

namespace fb {
namespace {

// Two unit quads side by side sharing the edge 1-4 (vertices 0 1 2 / 3 4 5 along x, y up):
// face 0 = 0 1 4 3, face 1 = 1 2 5 4, both counter-clockwise.
const std::vector<uint32_t> kSizes{4, 4};
const std::vector<uint32_t> kVertices{0, 1, 4, 3, 1, 2, 5, 4};

// The corners' coordinates when each quad maps onto its own place in the plane; `shift` moves the
// second quad's coordinates along u.
std::vector<Vec2f> strip_uvs(float shift) {
  return {{0, 0},         {1, 0},         {1, 1},         {0, 1},
          {1 + shift, 0}, {2 + shift, 0}, {2 + shift, 1}, {1 + shift, 1}};
}

TEST(FaceVarying, CornersWithTheSameCoordinatesShareAValue) {
  const FaceVaryingChannel c = join_uv_corners(kSizes, kVertices, 6, strip_uvs(0));
  EXPECT_EQ(c.value_count(), 6u);                     // one per vertex: no seam
  EXPECT_EQ(c.corner_values[1], c.corner_values[4]);  // vertex 1 in both faces
  EXPECT_EQ(c.corner_values[2], c.corner_values[7]);  // vertex 4
  EXPECT_EQ(c.values[2 * c.corner_values[5]], 2.f);
}

TEST(FaceVarying, CoordinatesApartByTheConnectLimitAreASeam) {
  // Blender joins corners closer than 1e-4 in u and v, and no others.
  const FaceVaryingChannel joined = join_uv_corners(kSizes, kVertices, 6, strip_uvs(0.5e-4f));
  EXPECT_EQ(joined.value_count(), 6u);
  const FaceVaryingChannel seam = join_uv_corners(kSizes, kVertices, 6, strip_uvs(2e-4f));
  EXPECT_EQ(seam.value_count(), 8u);  // vertices 1 and 4 split
  EXPECT_NE(seam.corner_values[1], seam.corner_values[4]);
  EXPECT_NE(seam.corner_values[2], seam.corner_values[7]);
  // A joined value keeps the last corner's coordinates (face order), as Blender's evaluator does.
  EXPECT_EQ(joined.values[2 * joined.corner_values[1]], 1 + 0.5e-4f);
}

TEST(FaceVarying, MirroredFacesDoNotJoin) {
  // The second quad mirrored in u: its shared corners have the first's coordinates, but its UV
  // winding is the other way round, and Blender keeps such faces apart.
  std::vector<Vec2f> uv = strip_uvs(0);
  uv[4] = {1, 0}, uv[5] = {0, 0}, uv[6] = {0, 1}, uv[7] = {1, 1};
  const FaceVaryingChannel c = join_uv_corners(kSizes, kVertices, 6, uv);
  EXPECT_EQ(c.value_count(), 8u);
  EXPECT_NE(c.corner_values[1], c.corner_values[4]);
}

TEST(FaceVarying, EveryCornerHasAValueInRange) {
  const FaceVaryingChannel c = join_uv_corners(kSizes, kVertices, 6, strip_uvs(3));
  ASSERT_EQ(c.corner_values.size(), kVertices.size());
  for (uint32_t v : c.corner_values)
    EXPECT_LT(v, c.value_count());
  EXPECT_EQ(c.value_count(), 8u);
}

}  // namespace
}  // namespace fb
