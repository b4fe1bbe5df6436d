// The glTF importer on small files written by tinygltf's own serialiser (tests/support).
#include "importers/gltf/gltf_importer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <filmback/camera_projection.h>

#include "core/plugin/instances.h"
#include "core/util/error.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

const std::vector<Vec3f> kQuad = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

Scene import_file(const std::filesystem::path& file) {
  Diagnostics diagnostics;
  return import_gltf(file, diagnostics);
}

// The pinhole formula straight from glTF's definition of yfov and aspectRatio (glTF 2.0 §3.10):
// camera space is the node's inverse, x right, y up, looking down -z.
Vec2d pinhole_raster(Vec3d camera_space, double yfov, double width, double height) {
  const double f = (height / 2) / std::tan(yfov / 2);
  return {width / 2 + f * camera_space.x / -camera_space.z,
          height / 2 - f * camera_space.y / -camera_space.z};
}

TEST(GltfImporter, CameraProjectsKnownWorldPointsAsThePinholeFormulaSays) {
  const double yfov = 0.6, width = 300, height = 200;
  GltfBuilder gltf;
  const int cam = gltf.perspective_camera(yfov, width / height, 0.1, 1000, "Hero");
  // A camera under a rotated, translated parent, placed with a column-major matrix, as exporters
  // do.
  GltfBuilder::Node camera_node;
  camera_node.camera = cam;
  const Transform local =
      Transform::translate({0.5, 2, 7}) * Transform::rotate({0.05, -0.2, 0.02, 0.98});
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      camera_node.matrix.push_back(local(r, c));
  const int child = gltf.node(camera_node, false);
  GltfBuilder::Node parent;
  parent.translation = {100, -3, 20};
  parent.rotation = {0, std::sin(0.3), 0, std::cos(0.3)};
  parent.children = {child};
  gltf.node(parent);
  const Scene scene = import_file(gltf.write(test::scratch_dir() / "camera.gltf"));
  ASSERT_EQ(scene.cameras.size(), 1u);
  const SceneCamera& camera = scene.cameras[0];
  EXPECT_EQ(camera.name, "Hero");
  ASSERT_TRUE(camera.intended_aspect.has_value());
  EXPECT_DOUBLE_EQ(*camera.intended_aspect, 1.5);

  const Transform world_from_camera = Transform::translate({100, -3, 20}) *
                                      Transform::rotate({0, std::sin(0.3), 0, std::cos(0.3)}) *
                                      local;
  const Transform camera_from_world = world_from_camera.inverse();
  auto library = test::loader().load(FB_KIND_CAMERA, "perspective");
  const fb_camera_setup setup =
      make_camera_setup(camera.physical, uint32_t(width), uint32_t(height));
  const CameraInstance plugin(library, BoundParams(library->descriptor(), {}), setup);
  const double fy = view_plane(setup).fy;
  for (Vec3d world :
       {Vec3d{100.5, -1, 13}, Vec3d{97, 0, 10}, Vec3d{104, -4, 2}, Vec3d{101, -2, 18.5}}) {
    const Vec3d p = camera_from_world.point(world);
    ASSERT_LT(p.z, 0) << "test point behind the camera";
    const Vec2d expected = pinhole_raster(p, yfov, width, height);
    // The camera's ray through the expected raster point must pass through the world point:
    // measure the miss in pixels at that depth.
    fb_camera_sample sample{float(expected.x), float(expected.y), 0, 0, 0};
    fb_camera_ray ray;
    plugin.generate_rays({&sample, 1}, &ray);
    const Vec3d origin = camera.world_from_camera.point(Vec3d(Vec3f(ray.origin)));
    const Vec3d dir = normalize(camera.world_from_camera.vector(Vec3d(Vec3f(ray.direction))));
    const Vec3d to_point = world - origin;
    const double miss_m = length(to_point - dir * dot(to_point, dir));
    EXPECT_LT(miss_m / -p.z * fy, 1e-4)
        << "world point " << world.x << "," << world.y << "," << world.z;
  }
}

TEST(GltfImporter, YfovWithoutAspectRatioKeepsTheVerticalFieldOfView) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.camera = gltf.perspective_camera(0.8, 0.0, 0.01, 0.0);
  gltf.node(node);
  const Scene scene = import_file(gltf.write(test::scratch_dir() / "no_aspect.gltf"));
  const PhysicalCamera& c = scene.cameras.at(0).physical;
  EXPECT_FALSE(scene.cameras[0].intended_aspect.has_value());
  EXPECT_TRUE(std::isinf(c.clip_far_m));  // absent zfar: infinite projection
  for (auto [w, h] : {std::pair{640u, 480u}, {300u, 900u}})
    EXPECT_NEAR(describe_camera(c, w, h).vertical_fov_deg, 0.8 * 180 / std::numbers::pi, 1e-10);
}

TEST(GltfImporter, OrthographicCameraBecomesBlendersOrthoScale) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.camera = gltf.orthographic_camera(4, 2.25, 0.1, 50);
  gltf.node(node);
  const Scene scene = import_file(gltf.write(test::scratch_dir() / "ortho.gltf"));
  const SceneCamera& c = scene.cameras.at(0);
  EXPECT_EQ(c.physical.projection, uint32_t(FB_PROJECTION_ORTHOGRAPHIC));
  EXPECT_DOUBLE_EQ(c.physical.ortho_scale_m, 8);
  EXPECT_DOUBLE_EQ(*c.intended_aspect, 4 / 2.25);
}

TEST(GltfImporter, EveryIndexTypeAndNonIndexedGiveTheSameTriangles) {
  GltfBuilder gltf;
  const int material = gltf.material({0.5f, 0.5f, 0.5f});
  std::vector<Vec3f> unrolled;
  for (uint32_t i : kQuadIndices)
    unrolled.push_back(kQuad[i]);
  for (int type : {5121, 5123, 5125}) {
    GltfBuilder::Node n;
    n.mesh = gltf.mesh(kQuad, kQuadIndices, material, type);
    gltf.node(n);
  }
  GltfBuilder::Node n;
  n.mesh = gltf.mesh(unrolled, {}, material, -1);
  gltf.node(n);
  for (const char* name : {"types.gltf", "types.glb"}) {
    const Scene scene = import_file(gltf.write(test::scratch_dir() / name));
    ASSERT_EQ(scene.meshes.size(), 4u);
    for (const TriangleMesh& mesh : scene.meshes) {
      ASSERT_EQ(mesh.triangle_count(), 2u);
      for (size_t i = 0; i < 6; ++i) {
        const Vec3f p = mesh.positions[mesh.indices[i]], q = kQuad[kQuadIndices[i]];
        EXPECT_EQ(p.x, q.x);
        EXPECT_EQ(p.y, q.y);
      }
    }
  }
}

TEST(GltfImporter, NodeHierarchyComposesParentAndChildAndSharesMeshes) {
  GltfBuilder gltf;
  const int mesh = gltf.mesh(kQuad, kQuadIndices, gltf.material({1, 1, 1}));
  GltfBuilder::Node leaf;
  leaf.mesh = mesh;
  leaf.translation = {0, 0, -2};
  leaf.scale = {2, 2, 2};
  const int child = gltf.node(leaf, false);
  GltfBuilder::Node root;
  root.mesh = mesh;
  root.translation = {10, 0, 0};
  root.rotation = {0, 0, std::sin(std::numbers::pi / 4),
                   std::cos(std::numbers::pi / 4)};  // 90 deg about z
  root.children = {child};
  gltf.node(root);
  const Scene scene = import_file(gltf.write(test::scratch_dir() / "tree.gltf"));
  ASSERT_EQ(scene.meshes.size(), 1u);  // one glTF mesh, two instances
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.triangle_count(), 4u);
  // leaf vertex (1, -1, 0): scaled to (2, -2, -2), rotated 90 deg about z to (2, 2, -2), moved by
  // +10 x.
  const Vec3d p = scene.instances[1].world_from_object.point({1, -1, 0});
  EXPECT_NEAR(p.x, 12, 1e-12);
  EXPECT_NEAR(p.y, 2, 1e-12);
  EXPECT_NEAR(p.z, -2, 1e-12);
}

TEST(GltfImporter, EmissionStrengthAndPhotometricLightsAreConverted) {
  GltfBuilder gltf;
  const int lamp = gltf.material({0, 0, 0}, {1.0f, 0.5f, 0.25f}, 8.0);
  GltfBuilder::Node quad;
  quad.mesh = gltf.mesh(kQuad, kQuadIndices, lamp);
  gltf.node(quad);
  GltfBuilder::Node bulb;
  bulb.light = gltf.point_light({1, 0.5, 1}, 683 * 10.0);  // Blender: 10 W/sr * 683 lm/W
  bulb.translation = {1, 2, 3};
  gltf.node(bulb);
  const Scene scene = import_file(gltf.write(test::scratch_dir() / "lights.gltf"));
  const Material& m = scene.materials.at(0);
  EXPECT_FLOAT_EQ(m.emission.x, 8.f);
  EXPECT_FLOAT_EQ(m.emission.z, 2.f);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_NEAR(scene.lights[0].intensity.x, 10.f, 1e-5);
  EXPECT_NEAR(scene.lights[0].intensity.y, 5.f, 1e-5);
  EXPECT_NEAR(scene.lights[0].world_from_light.translation().z, 3, 0);
}

TEST(GltfImporter, PrimitiveWithoutMaterialGetsGltfDefaultWhite) {
  GltfBuilder gltf;
  GltfBuilder::Node n;
  n.mesh = gltf.mesh(kQuad, kQuadIndices, -1);
  gltf.node(n);
  const Scene scene = import_file(gltf.write(test::scratch_dir() / "default_material.gltf"));
  const Material& m = scene.materials.at(scene.meshes.at(0).material);
  EXPECT_EQ(m.base_color.x, 1.f);
  EXPECT_EQ(m.emission.x, 0.f);
}

TEST(GltfImporter, MissingFileIsAnInputErrorNamingIt) {
  try {
    import_file(test::scratch_dir() / "nowhere.gltf");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere.gltf: no such file"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace fb
