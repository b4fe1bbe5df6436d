// glTF skins (importers/gltf/gltf_skin.h, core/scene/mesh_deformation.h): posed vertices against
// the closed form of glTF 2.0 §3.8.3's skinning equation, and hostile skins refused or
// normalised with a message naming the JSON path.
#include "importers/gltf/gltf_skin.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "importers/gltf/gltf_importer.h"
#include "support/expect_vec.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"

namespace fb {
namespace {

using test::GltfBuilder;

using test::expect_vertex_near;

// A rotation by `angle` about +Z as a glTF quaternion (x, y, z, w).
std::array<double, 4> about_z(double angle) {
  return {0, 0, std::sin(angle / 2), std::cos(angle / 2)};
}

// Two joints: the root at the origin and its child one metre up +Y, rotated about +Z from 0 at
// t = 0 to `bend` at t = 1. The triangle's first vertex follows the root, its second the child,
// its third both equally. The mesh node's own translation must be ignored (glTF 2.0 §3.8.3).
struct Bend {
  GltfBuilder gltf;
  double bend = 0.7;
  Bend() {
    const int mesh = gltf.mesh({{1, 0, 0}, {1, 2, 0}, {1, 1.5f, 0}}, {0, 1, 2}, -1, 5125,
                               {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}});
    gltf.skin_weights(mesh, 0, {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0},
                      {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0});
    GltfBuilder::Node child;
    child.translation = {0, 1, 0};
    const int child_joint = gltf.node(child, false);
    GltfBuilder::Node root;
    root.children = {child_joint};
    const int root_joint = gltf.node(root);
    // The child's bind pose is one metre up: its inverse bind matrix moves one metre down.
    const std::vector<float> inverse_binds = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    GltfBuilder::Node skinned;
    skinned.mesh = mesh;
    skinned.skin = gltf.skin({root_joint, child_joint}, inverse_binds);
    skinned.translation = {5, 5, 5};
    gltf.node(skinned);
    const auto q = about_z(bend);
    gltf.animate(child_joint, "rotation", {0, 1},
                 {0, 0, 0, 1, float(q[0]), float(q[1]), float(q[2]), float(q[3])});
  }
};

// The child's rotation R about +Z applied about its origin (0, 1, 0).
Vec3d bent(Vec3d v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  const double x = v.x, y = v.y - 1;
  return {c * x - s * y, s * x + c * y + 1, v.z};
}

TEST(GltfSkin, TwoJointBendMatchesTheClosedFormAtTheFrame) {
  Bend file;
  Scene scene = test::import_built(file.gltf, "bend.gltf");
  ASSERT_EQ(scene.deformations.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].node_index, kNoNode);  // placed by its joints, not its node
  const TriangleMesh mesh = posed_mesh(scene, scene.deformations[0], 1.0);
  expect_vertex_near(mesh.positions[0], {1, 0, 0});
  expect_vertex_near(mesh.positions[1], bent({1, 2, 0}, file.bend));
  const Vec3d mid = bent({1, 1.5, 0}, file.bend);
  expect_vertex_near(mesh.positions[2], {0.5 * (1 + mid.x), 0.5 * (1.5 + mid.y), 0});
  expect_vertex_near(mesh.normals[0], {1, 0, 0});
  expect_vertex_near(mesh.normals[1], {std::cos(file.bend), std::sin(file.bend), 0});
}

TEST(GltfSkin, HalfwayThroughTheAnimationTheBendIsHalfAsLarge) {
  Bend file;
  Scene scene = test::import_built(file.gltf, "bend.gltf");
  // Slerp between identity and `bend` about one axis.
  expect_vertex_near(posed_mesh(scene, scene.deformations[0], 0.5).positions[1],
                     bent({1, 2, 0}, file.bend / 2));
}

// A root joint scaled (2, 1, 1), its child one metre up and turned 90 degrees about +Z, inverse
// bind matrices the identity: v' = S · (T · R · v) for the child's vertices.
TEST(GltfSkin, JointHierarchyWithNonUniformScale) {
  GltfBuilder gltf;
  const float h = float(std::sqrt(0.5));
  const int mesh = gltf.mesh({{0, 1, 0}, {1, 0, 0}, {0, 0, 1}}, {0, 1, 2}, -1, 5125,
                             {{h, h, 0}, {0, 1, 0}, {0, 0, 1}});
  gltf.skin_weights(mesh, 0, {1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0},
                    {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
  GltfBuilder::Node child;
  child.translation = {0, 1, 0};
  child.rotation = about_z(std::numbers::pi / 2);
  const int child_joint = gltf.node(child, false);
  GltfBuilder::Node root;
  root.scale = {2, 1, 1};
  root.children = {child_joint};
  const int root_joint = gltf.node(root);
  GltfBuilder::Node skinned;
  skinned.mesh = mesh;
  skinned.skin = gltf.skin({root_joint, child_joint});
  gltf.node(skinned);
  Scene scene = test::import_built(gltf, "scaled.gltf");
  const TriangleMesh posed = posed_mesh(scene, scene.deformations[0], 0.0);
  // Child: R (0, 1, 0) = (-1, 0, 0); + (0, 1, 0); x doubled.
  expect_vertex_near(posed.positions[0], {-2, 1, 0});
  expect_vertex_near(posed.positions[1], {2, 0, 0});  // the root's: x doubled
  expect_vertex_near(posed.positions[2], {0, 1, 1});  // child: R leaves +Z, T lifts it
  // Normals by the inverse transpose S^-1 · R: R (h, h, 0) = (-h, h, 0), x halved.
  expect_vertex_near(posed.normals[0], Vec3d{-0.5, 1, 0} / std::sqrt(1.25));
  expect_vertex_near(posed.normals[1], {0, 1, 0});
  expect_vertex_near(posed.normals[2], {0, 0, 1});
}

// A skin whose one joint stands at the origin and never moves changes nothing, bit for bit.
TEST(GltfSkin, StillJointsLeaveTheMeshBitIdenticalToTheUnskinnedOne) {
  const std::vector<Vec3f> positions = {{0.1f, -0.3f, 2}, {1.7f, 0.2f, -1}, {-0.4f, 1.1f, 0.3f}};
  const std::vector<Vec3f> normals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  GltfBuilder plain;
  GltfBuilder::Node node;
  node.mesh = plain.mesh(positions, {0, 1, 2}, -1, 5125, normals);
  plain.node(node);
  GltfBuilder skinned;
  GltfBuilder::Node joint;
  const int joint_node = skinned.node(joint);
  node.mesh = skinned.mesh(positions, {0, 1, 2}, -1, 5125, normals);
  skinned.skin_weights(node.mesh, 0, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
                       {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
  node.skin = skinned.skin({joint_node});
  skinned.node(node);
  const Scene expected = test::import_built(plain, "plain.gltf");
  Scene scene = test::import_built(skinned, "skinned.gltf");
  const TriangleMesh posed = posed_mesh(scene, scene.deformations[0], 0.0);
  for (size_t v = 0; v < positions.size(); ++v) {
    EXPECT_EQ(posed.positions[v].x, expected.meshes[0].positions[v].x);
    EXPECT_EQ(posed.positions[v].y, expected.meshes[0].positions[v].y);
    EXPECT_EQ(posed.positions[v].z, expected.meshes[0].positions[v].z);
    EXPECT_EQ(posed.normals[v].x, expected.meshes[0].normals[v].x);
    EXPECT_EQ(posed.normals[v].y, expected.meshes[0].normals[v].y);
    EXPECT_EQ(posed.normals[v].z, expected.meshes[0].normals[v].z);
  }
}

// One vertex skinned to joint `joint_index` of a one-joint skin with weights `weights` and
// inverse bind matrix `inverse_bind`.
std::filesystem::path hostile_skin(uint16_t joint_index, std::vector<float> weights,
                                   std::vector<float> inverse_bind) {
  GltfBuilder gltf;
  GltfBuilder::Node joint;
  const int joint_node = gltf.node(joint);
  GltfBuilder::Node node;
  node.mesh = gltf.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, -1);
  gltf.skin_weights(node.mesh, 0, {joint_index, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
                    {weights[0], weights[1], weights[2], weights[3], 1, 0, 0, 0, 1, 0, 0, 0});
  node.skin = gltf.skin({joint_node}, inverse_bind);
  gltf.node(node);
  return gltf.write(test::scratch_dir() / "hostile.gltf");
}

const std::vector<float> kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

TEST(GltfSkin, JointIndexPastTheSkinIsRefusedNamingTheAttribute) {
  const std::string error = test::import_error(hostile_skin(3, {1, 0, 0, 0}, kIdentity));
  EXPECT_NE(error.find("meshes[0].primitives[0].attributes.JOINTS_0"), std::string::npos) << error;
  EXPECT_NE(error.find("names joint 3, but the skin has 1 joints"), std::string::npos) << error;
}

TEST(GltfSkin, NonFiniteInverseBindMatrixIsRefused) {
  std::vector<float> nan_bind = kIdentity;
  nan_bind[5] = std::numeric_limits<float>::quiet_NaN();
  const std::string error = test::import_error(hostile_skin(0, {1, 0, 0, 0}, nan_bind));
  EXPECT_NE(error.find("skins[0].inverseBindMatrices"), std::string::npos) << error;
  EXPECT_NE(error.find("not a finite number"), std::string::npos) << error;
}

TEST(GltfSkin, AllZeroWeightsAreRefused) {
  const std::string error = test::import_error(hostile_skin(0, {0, 0, 0, 0}, kIdentity));
  EXPECT_NE(error.find("attributes.WEIGHTS_0"), std::string::npos) << error;
  EXPECT_NE(error.find("vertex 0's weights are all zero"), std::string::npos) << error;
}

TEST(GltfSkin, WeightsNotSummingToOneAreNormalisedWithAWarning) {
  Diagnostics diagnostics;
  Scene scene = import_gltf(hostile_skin(0, {0.25f, 0.25f, 0, 0}, kIdentity), diagnostics);
  ASSERT_EQ(diagnostics.messages().size(), 1u);
  EXPECT_NE(diagnostics.messages()[0].find("meshes[0].primitives[0].attributes.WEIGHTS_0"),
            std::string::npos)
      << diagnostics.messages()[0];
  ASSERT_TRUE(scene.deformations[0].skin.has_value());
  const SkinBinding& skin = *scene.deformations[0].skin;
  EXPECT_FLOAT_EQ(skin.weights[0] + skin.weights[1], 1.f);
  EXPECT_FLOAT_EQ(skin.weights[0], 0.5f);
}

TEST(GltfSkin, AJointListedTwiceIsRefused) {
  GltfBuilder gltf;
  GltfBuilder::Node joint;
  const int joint_node = gltf.node(joint);
  GltfBuilder::Node node;
  node.mesh = gltf.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, -1);
  gltf.skin_weights(node.mesh, 0, std::vector<uint16_t>(12, 0),
                    {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
  node.skin = gltf.skin({joint_node, joint_node});
  gltf.node(node);
  const std::string error = test::import_error(gltf.write(test::scratch_dir() / "twice.gltf"));
  EXPECT_NE(error.find("skins[0].joints[1]: nodes[0] is a joint of this skin already"),
            std::string::npos)
      << error;
}

TEST(GltfSkin, JointOutsideTheRenderedSceneIsRefused) {
  GltfBuilder gltf;
  GltfBuilder::Node joint;
  const int orphan = gltf.node(joint, false);  // in no scene
  GltfBuilder::Node node;
  node.mesh = gltf.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, -1);
  gltf.skin_weights(node.mesh, 0, std::vector<uint16_t>(12, 0),
                    {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
  node.skin = gltf.skin({orphan});
  gltf.node(node);
  const std::string error = test::import_error(gltf.write(test::scratch_dir() / "orphan.gltf"));
  EXPECT_NE(error.find("skins[0].joints[0]"), std::string::npos) << error;
}

}  // namespace
}  // namespace fb
