// FILMBACK_deformation (importers/gltf/gltf_deformation.h): an exporter's evaluated shapes
// replace the node's skin and morph targets, are placed by the node unless in world space, blend
// linearly between their times, and hostile ones are refused naming the JSON path.
#include "importers/gltf/gltf_deformation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "support/expect_vec.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"

namespace fb {
namespace {

using test::expect_vertex_near;
using test::GltfBuilder;

const std::vector<Vec3f> kEvaluatedTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

// The triangle moved `dx` along +X.
std::vector<Vec3f> slid_triangle(float dx) {
  std::vector<Vec3f> out = kEvaluatedTriangle;
  for (Vec3f& p : out)
    p.x += dx;
  return out;
}

// A triangle with a morph target on a node translated 5 m along +Y, carrying evaluated shapes
// at `times_s`, the k-th slid k metres along +X.
struct EvaluatedFile {
  GltfBuilder gltf;
  int node = -1;
  explicit EvaluatedFile(const std::vector<double>& times_s, bool world_space = false) {
    GltfBuilder::Node n;
    n.mesh = gltf.mesh(kEvaluatedTriangle, {0, 1, 2}, -1);
    gltf.morph_target(n.mesh, {{0, 0, 3}, {0, 0, 3}, {0, 0, 3}});
    gltf.morph_weights(n.mesh, {1.0});
    n.translation = {0, 5, 0};
    node = gltf.node(n);
    std::vector<std::vector<Vec3f>> positions, normals;
    for (size_t k = 0; k < times_s.size(); ++k) {
      positions.push_back(slid_triangle(float(k)));
      normals.push_back(std::vector<Vec3f>(3, Vec3f{0, 0, 1}));
    }
    gltf.evaluated_shapes(node, times_s, positions, normals, world_space);
  }
};

TEST(GltfDeformation, EvaluatedShapesReplaceTheMorphTargetsAndTheNodePlacesThem) {
  EvaluatedFile file({-0.01, 0, 0.01});
  const Scene scene = test::import_built(file.gltf, "evaluated.gltf");
  ASSERT_EQ(scene.deformations.size(), 1u);
  const MeshDeformation& d = scene.deformations[0];
  EXPECT_TRUE(d.morph.empty());
  EXPECT_FALSE(d.skin);
  ASSERT_EQ(d.evaluated.shapes.size(), 3u);
  EXPECT_EQ(d.evaluated.times_s, (std::vector<double>{-0.01, 0, 0.01}));
  expect_vertex_near(d.evaluated.shapes[2].positions[1], {3, 0, 0});
  ASSERT_EQ(scene.instances.size(), 1u);
  expect_vertex_near(Vec3f(scene.instances[0].world_from_object.point(Vec3d{0, 0, 0})), {0, 5, 0});
}

TEST(GltfDeformation, WorldSpaceShapesAreDrawnAtTheIdentity) {
  EvaluatedFile file({0}, true);
  const Scene scene = test::import_built(file.gltf, "evaluated_world.gltf");
  ASSERT_EQ(scene.instances.size(), 1u);
  expect_vertex_near(Vec3f(scene.instances[0].world_from_object.point(Vec3d{0, 0, 0})), {0, 0, 0});
  EXPECT_EQ(scene.instances[0].node_index, kNoNode);
}

// Between two times a vertex moves linearly (as Embree interpolates); outside, it stays.
TEST(GltfDeformation, ShapesBlendLinearlyBetweenTheirTimesAndHoldBeyond) {
  EvaluatedShapes shapes;
  shapes.times_s = {-1, 0, 2};
  for (float dx : {0.f, 1.f, 5.f})
    shapes.shapes.push_back({slid_triangle(dx), std::vector<Vec3f>(3, Vec3f{0, 0, 1})});
  expect_vertex_near(shapes.at(-0.25).positions[0], {0.75, 0, 0});
  expect_vertex_near(shapes.at(1.0).positions[0], {3, 0, 0});
  expect_vertex_near(shapes.at(-7).positions[0], {0, 0, 0});
  expect_vertex_near(shapes.at(9).positions[2], {5, 1, 0});
  expect_vertex_near(shapes.at(0.5).normals[1], {0, 0, 1});
}

// The error importing a triangle whose FILMBACK_deformation has these times and shapes.
std::string evaluated_error(const std::vector<double>& times_s,
                            const std::vector<std::vector<Vec3f>>& positions,
                            const std::vector<std::vector<Vec3f>>& normals = {}) {
  GltfBuilder gltf;
  GltfBuilder::Node n;
  n.mesh = gltf.mesh(kEvaluatedTriangle, {0, 1, 2}, -1);
  gltf.evaluated_shapes(gltf.node(n), times_s, positions, normals);
  return test::import_error(gltf.write(test::scratch_dir() / "evaluated_bad.gltf"));
}

TEST(GltfDeformation, HostileShapesAreRefusedNamingTheJsonPath) {
  const std::string ext = "nodes[0].extensions.FILMBACK_deformation";
  const auto expect_error = [](const std::string& error, const std::string& expected) {
    EXPECT_NE(error.find(expected), std::string::npos) << error;
  };
  const std::vector<Vec3f>& t = kEvaluatedTriangle;
  expect_error(evaluated_error({0.1, 0}, {t, t}), ext + ".times_s: time 1 does not follow");
  expect_error(evaluated_error({}, {}), ext + ".times_s: missing or empty");
  std::vector<double> too_many;
  for (size_t k = 0; k <= kMaxEvaluatedShapes; ++k)
    too_many.push_back(double(k));
  expect_error(evaluated_error(too_many, {t}), ext + ".times_s");
  expect_error(evaluated_error({0, 1}, {t}),
               ext + ".primitives[0].positions: 1 accessors for 2 times");
  expect_error(evaluated_error({0}, {{t[0], t[1]}}),
               ext + ".primitives[0].positions[0]: accessor of 2 values; expected one per vertex");
  expect_error(evaluated_error({0}, {t}, {{{0, 0, 1}, {0, 0, 0}, {0, 0, 1}}}),
               ext + ".primitives[0].normals[0]: normal 1 has zero length");
  std::vector<Vec3f> bad = t;
  bad[1].y = std::numeric_limits<float>::quiet_NaN();
  expect_error(evaluated_error({0, 1}, {t, bad}), ext + ".primitives[0].positions[1]");
}

}  // namespace
}  // namespace fb
