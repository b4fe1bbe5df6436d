// Sparse accessors (glTF 2.0 §3.6.2.3; importers/gltf/gltf_accessors.cpp): a morph target of
// zeros but at a few vertices, and positions with a few of their base values replaced, against
// the closed form; hostile sparse objects refused naming the JSON path.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "support/expect_vec.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"

namespace fb {
namespace {

using test::expect_vertex_near;
using test::GltfBuilder;

const std::vector<Vec3f> kSparseTriangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

class SparseMorphTarget : public testing::TestWithParam<int> {};

// A target that is zero but at vertices 1 and 2, read through indices of each component type:
// the morphed vertices are v + w · d, vertex 0 untouched.
TEST_P(SparseMorphTarget, DisplacesOnlyTheVerticesAtItsIndices) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh = gltf.mesh(kSparseTriangle, {0, 1, 2}, -1);
  gltf.morph_target_accessor(
      node.mesh, gltf.sparse_vec3(3, {1, 2}, {{0, 0, 2}, {0.5f, -1, 0}}, -1, GetParam()));
  node.weights = {0.25};
  gltf.node(node);
  const Scene scene = test::import_built(gltf, "sparse_target.gltf");
  ASSERT_EQ(scene.deformations.size(), 1u);
  const TriangleMesh mesh = posed_mesh(scene, scene.deformations[0], 0);
  expect_vertex_near(mesh.positions[0], Vec3d{0, 0, 0});
  expect_vertex_near(mesh.positions[1], Vec3d{1, 0, 0.5});
  expect_vertex_near(mesh.positions[2], Vec3d{0.125, 0.75, 0});
}

INSTANTIATE_TEST_SUITE_P(IndexTypes, SparseMorphTarget, testing::Values(5121, 5123, 5125));

// POSITION whose base data is the triangle, with vertex 2 replaced: the other two stay bit for
// bit, the replaced one is the sparse value.
TEST(GltfSparse, ValuesReplaceTheirBaseElements) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh = gltf.mesh(kSparseTriangle, {0, 1, 2}, -1);
  gltf.attribute(node.mesh, "POSITION", gltf.sparse_vec3(3, {2}, {{0, 3, -1}}, 0));
  gltf.node(node);
  const Scene scene = test::import_built(gltf, "sparse_positions.gltf");
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.positions.size(), 3u);
  for (size_t v = 0; v < 2; ++v) {
    EXPECT_EQ(mesh.positions[v].x, kSparseTriangle[v].x) << v;
    EXPECT_EQ(mesh.positions[v].y, kSparseTriangle[v].y) << v;
    EXPECT_EQ(mesh.positions[v].z, kSparseTriangle[v].z) << v;
  }
  expect_vertex_near(mesh.positions[2], Vec3d{0, 3, -1});
}

// The error importing a triangle whose morph target is the given sparse accessor.
std::string sparse_target_error(const char* name, size_t count,
                                const std::vector<uint32_t>& indices,
                                const std::vector<Vec3f>& values, int sparse_count = -1) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh = gltf.mesh(kSparseTriangle, {0, 1, 2}, -1);
  const int target = gltf.sparse_vec3(count, indices, values, -1, 5125, sparse_count);
  gltf.morph_target_accessor(node.mesh, target);
  node.weights = {1};
  gltf.node(node);
  return test::import_error(gltf.write(test::scratch_dir() / name));
}

TEST(GltfSparse, AnIndexPastTheAccessorIsRefused) {
  const std::string error =
      sparse_target_error("sparse_range.gltf", 3, {0, 7}, {{0, 1, 0}, {0, 1, 0}});
  EXPECT_NE(error.find(".sparse.indices: element 1 is 7, past the accessor's 3 elements"),
            std::string::npos)
      << error;
}

TEST(GltfSparse, IndicesThatDoNotIncreaseAreRefused) {
  const std::string error =
      sparse_target_error("sparse_order.gltf", 3, {2, 1}, {{0, 1, 0}, {0, 1, 0}});
  EXPECT_NE(error.find(".sparse.indices: element 1 is 1, not above the one before it"),
            std::string::npos)
      << error;
}

TEST(GltfSparse, ACountLargerThanTheAccessorsIsRefused) {
  const std::string error = sparse_target_error("sparse_count.gltf", 3, {0, 1, 2, 3},
                                                {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}});
  EXPECT_NE(error.find(".sparse.count: 4, expected 1 to the accessor's count (3)"),
            std::string::npos)
      << error;
}

// sparse.count says 3, but the file holds two indices and two values: nothing past them is read.
TEST(GltfSparse, ACountLargerThanItsIndicesHoldIsRefused) {
  const std::string error =
      sparse_target_error("sparse_short.gltf", 3, {0, 1}, {{0, 1, 0}, {0, 1, 0}}, 3);
  EXPECT_NE(error.find(".sparse.indices"), std::string::npos) << error;
  EXPECT_NE(error.find("do not fit in bufferViews["), std::string::npos) << error;
}

TEST(GltfSparse, ANonFiniteValueIsRefusedNamingIt) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::string error =
      sparse_target_error("sparse_nan.gltf", 3, {0, 2}, {{0, 1, 0}, {0, nan, 0}});
  EXPECT_NE(error.find(".sparse.values: element 1 (for element 2) is not a finite number"),
            std::string::npos)
      << error;
}

// Without a bufferView nothing in the file bounds the count: a few bytes may not claim 2^24 + 1
// elements (checked before anything is allocated).
TEST(GltfSparse, ZerosBeyondTheBoundAreRefusedBeforeAllocating) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh = gltf.mesh(kSparseTriangle, {0, 1, 2}, -1);
  gltf.attribute(node.mesh, "POSITION", gltf.sparse_vec3((size_t(1) << 24) + 1, {0}, {{0, 1, 0}}));
  gltf.node(node);
  const std::string error = test::import_error(gltf.write(test::scratch_dir() / "sparse_big.gltf"));
  EXPECT_NE(error.find("16777217 elements without a bufferView; at most 16777216"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace fb
