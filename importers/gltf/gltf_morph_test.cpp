// glTF morph targets (importers/gltf/gltf_morph.h, core/scene/mesh_deformation.h): displaced
// vertices against v + Σ w_t · d_t (glTF 2.0 §3.7.2.2) with static, overridden and animated
// weights, morphing before skinning, and hostile targets refused naming the JSON path.
#include "importers/gltf/gltf_morph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/expect_vec.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"

namespace fb {
namespace {

using test::GltfBuilder;

using test::expect_vertex_near;

// A triangle with two targets: the first lifts vertex 0 by +Y and tilts its normal toward +X,
// the second pushes vertex 1 along +X and vertex 2 along -Z.
struct TwoTargets {
  GltfBuilder gltf;
  int mesh;
  TwoTargets() {
    mesh = gltf.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, -1, 5125,
                     {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    gltf.morph_target(mesh, {{0, 1, 0}, {0, 0, 0}, {0, 0, 0}}, {{1, 0, -1}, {0, 0, 0}, {0, 0, 0}});
    gltf.morph_target(mesh, {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}});
  }
  // Vertex positions for weights (a, b).
  static std::array<Vec3d, 3> expected(double a, double b) {
    return {Vec3d{0, a, 0}, Vec3d{1 + b, 0, 0}, Vec3d{0, 1, -b}};
  }
  Scene import(const GltfBuilder::Node& node) {
    gltf.node(node);
    return test::import_built(gltf, "morph.gltf");
  }
};

void expect_weights(const Scene& scene, double time_s, double a, double b) {
  ASSERT_EQ(scene.deformations.size(), 1u);
  const TriangleMesh mesh = posed_mesh(scene, scene.deformations[0], time_s);
  const auto expected = TwoTargets::expected(a, b);
  for (size_t v = 0; v < 3; ++v)
    expect_vertex_near(mesh.positions[v], expected[v]);
}

TEST(GltfMorph, TheMeshsWeightsDisplaceVerticesAndNormals) {
  TwoTargets file;
  file.gltf.morph_weights(file.mesh, {0.25, 0.5});
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  node.translation = {3, 0, 0};  // a morphed mesh stays placed by its node
  Scene scene = file.import(node);
  expect_weights(scene, 0, 0.25, 0.5);
  // (0, 0, 1) + 0.25 (1, 0, -1) = (0.25, 0, 0.75), normalised.
  expect_vertex_near(posed_mesh(scene, scene.deformations[0], 0).normals[0],
                     Vec3d{0.25, 0, 0.75} / std::sqrt(0.625));
  EXPECT_DOUBLE_EQ(scene.world_from_object(scene.instances[0], 0).translation().x, 3);
}

TEST(GltfMorph, TheNodesWeightsOverrideTheMeshs) {
  TwoTargets file;
  file.gltf.morph_weights(file.mesh, {0.25, 0.5});
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  node.weights = {1, -0.5};
  Scene scene = file.import(node);
  expect_weights(scene, 0, 1, -0.5);
}

TEST(GltfMorph, ZeroWeightsLeaveTheBaseShapeBitForBit) {
  TwoTargets file;
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  Scene scene = file.import(node);
  const TriangleMesh& base = scene.meshes[0];
  const TriangleMesh posed = posed_mesh(scene, scene.deformations[0], 0);
  for (size_t v = 0; v < 3; ++v) {
    EXPECT_EQ(posed.positions[v].y, base.positions[v].y);
    EXPECT_EQ(posed.normals[v].x, base.normals[v].x);
  }
}

TEST(GltfMorph, LinearWeightAnimationAtTheFrame) {
  TwoTargets file;
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  const int n = file.gltf.node(node);
  file.gltf.animate(n, "weights", {0, 2}, {0, 0, 1, 0.5f});
  Scene scene = test::import_built(file.gltf, "linear.gltf");
  expect_weights(scene, 0.5, 0.25, 0.125);
  expect_weights(scene, 5, 1, 0.5);  // clamped after the last key
}

TEST(GltfMorph, StepWeightAnimationHoldsTheKey) {
  TwoTargets file;
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  const int n = file.gltf.node(node);
  file.gltf.animate(n, "weights", {0, 2}, {0.5f, 0.25f, 1, 1}, "STEP");
  Scene scene = test::import_built(file.gltf, "step.gltf");
  expect_weights(scene, 1.9, 0.5, 0.25);
}

// Flat tangents from 0 at t = 0 to 1 at t = 1 make glTF's Hermite spline the smoothstep
// 3s² - 2s³: 0.15625 at s = 1/4.
TEST(GltfMorph, CubicSplineWeightAnimationIsTheHermiteCurve) {
  TwoTargets file;
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  const int n = file.gltf.node(node);
  // Per key: in-tangents (2), values (2), out-tangents (2).
  file.gltf.animate(n, "weights", {0, 1}, {0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0}, "CUBICSPLINE");
  Scene scene = test::import_built(file.gltf, "cubic.gltf");
  expect_weights(scene, 0.25, 0.15625, 0.3125);
}

// Morphing comes first (glTF 2.0 §3.7.2.2), then the skin: a joint turned 90° about +Z carries
// the morphed vertex, v' = R (v + w d).
TEST(GltfMorph, TargetsApplyBeforeTheSkin) {
  TwoTargets file;
  file.gltf.morph_weights(file.mesh, {1, 1});
  file.gltf.skin_weights(file.mesh, 0, std::vector<uint16_t>(12, 0),
                         {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
  GltfBuilder::Node joint;
  joint.rotation = {0, 0, std::sin(std::numbers::pi / 4), std::cos(std::numbers::pi / 4)};
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  node.skin = file.gltf.skin({file.gltf.node(joint)});
  Scene scene = file.import(node);
  const TriangleMesh mesh = posed_mesh(scene, scene.deformations[0], 0);
  // Morphed: (0, 1, 0), (2, 0, 0), (0, 1, -1); R (x, y, z) = (-y, x, z).
  expect_vertex_near(mesh.positions[0], {-1, 0, 0});
  expect_vertex_near(mesh.positions[1], {0, 2, 0});
  expect_vertex_near(mesh.positions[2], {-1, 0, -1});
}

TEST(GltfMorph, MoreTargetsThanTheBoundAreRefusedBeforeReading) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh = gltf.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, -1);
  for (size_t t = 0; t <= gltf::kMaxMorphTargets; ++t)
    gltf.morph_target(node.mesh, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  gltf.node(node);
  const std::string error = test::import_error(gltf.write(test::scratch_dir() / "many.gltf"));
  EXPECT_NE(error.find("meshes[0].primitives[0].targets: 1025 morph targets; expected at most"),
            std::string::npos)
      << error;
}

TEST(GltfMorph, TooManyDisplacementsAreRefusedBeforeReading) {
  const size_t vertices = gltf::kMaxMorphDisplacements / 64 + 1;
  std::vector<Vec3f> positions(vertices, Vec3f{0, 0, 0});
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh = gltf.mesh(positions, {0, 1, 2}, -1);
  for (size_t t = 0; t < 64; ++t)
    gltf.morph_target(node.mesh, {{0, 0, 0}});  // never read: the count is refused first
  gltf.node(node);
  const std::string error = test::import_error(gltf.write(test::scratch_dir() / "wide.gltf"));
  EXPECT_NE(error.find("meshes[0].primitives[0].targets: 64 morph targets of"), std::string::npos)
      << error;
}

TEST(GltfMorph, WeightsOfTheWrongLengthAreRefused) {
  TwoTargets file;
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  node.weights = {1, 0, 0};
  file.gltf.node(node);
  const std::string error =
      test::import_error(file.gltf.write(test::scratch_dir() / "weights.gltf"));
  EXPECT_NE(error.find("nodes[0].weights: 3 weights for 2 morph targets"), std::string::npos)
      << error;
}

TEST(GltfMorph, AnimatedWeightsOfTheWrongCountAreRefused) {
  TwoTargets file;
  GltfBuilder::Node node;
  node.mesh = file.mesh;
  const int n = file.gltf.node(node);
  file.gltf.animate(n, "weights", {0, 1}, {0, 0, 1});
  const std::string error =
      test::import_error(file.gltf.write(test::scratch_dir() / "animated.gltf"));
  EXPECT_NE(error.find("animations[0].samplers[0].output"), std::string::npos) << error;
}

}  // namespace
}  // namespace fb
