// Skinned meshes and evaluated shapes through the whole render (core/accel/render_geometry.cpp
// poses them at their motion steps): a joint's animation moves what the image shows at the frame
// and blurs it over an open shutter, a still skin builds no motion data, and a skin that changes
// nothing renders the unskinned mesh's image bit for bit. Evaluated shapes (FILMBACK_deformation):
// the shape at the frame is what a closed shutter shows, an open one blurs over the file's shapes
// with as many motion steps as the file has, and shapes that do not change build none.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/accel/deformation_steps.h"
#include "core/accel/render_geometry.h"
#include "core/render/render_job.h"
#include "core/util/error.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

// A grey triangle filling the view of a camera 3 m up +Z; with `skinned`, bound to one joint
// whose translation goes from the origin at t = 0 to 10 m along +X at t = 1 (when `animated`),
// out of the view.
Scene skinned_triangle(bool skinned, bool animated) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh =
      gltf.mesh({{-5, -5, 0}, {5, -5, 0}, {0, 5, 0}}, {0, 1, 2}, gltf.material({0.5f, 0.5f, 0.5f}));
  if (skinned) {
    GltfBuilder::Node joint;
    const int joint_node = gltf.node(joint);
    gltf.skin_weights(node.mesh, 0, std::vector<uint16_t>(12, 0),
                      {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
    node.skin = gltf.skin({joint_node});
    if (animated) gltf.animate(joint_node, "translation", {0, 1}, {0, 0, 0, 10, 0, 0});
  }
  gltf.node(node);
  GltfBuilder::Node camera;
  camera.camera = gltf.perspective_camera(0.5, 1.0, 0.1, 100);
  camera.translation = {0, 0, 3};
  gltf.node(camera);
  return test::import_built(gltf, "skinned.gltf");
}

Image render_skinned_frame(const Scene& scene, double frame, bool open_shutter = false) {
  RenderOptions options;
  if (open_shutter) options.shutter_s = Vec2d{0.0, 1.0};
  options.width = 16, options.height = 16, options.samples_per_pixel = 4;
  options.integrator = "path:max_depth=2";
  options.background = Rgb{1.f, 1.f, 1.f};
  options.frame = frame, options.fps = 1;
  options.show_progress = false;
  return RenderJob(scene, options, test::loader()).run().image;
}

double skinned_mean_red(const Image& image) {
  double sum = 0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      sum += image.at(x, y, 0);
  return sum / (image.width * image.height);
}

TEST(SkinnedRender, TheJointsAnimationAtTheFrameMovesTheMesh) {
  const Scene scene = skinned_triangle(true, true);
  // Frame 0: the grey triangle (albedo 0.5 under a sky of 1); frame 1: moved out, only the sky.
  EXPECT_NEAR(skinned_mean_red(render_skinned_frame(scene, 0)), 0.5, 0.1);
  EXPECT_EQ(skinned_mean_red(render_skinned_frame(scene, 1)), 1.0);
}

// Over a shutter open from t = 0 to 1 the triangle leaves the view: the image lies between the
// sharp triangle's and the sky's.
void expect_blur_leaving_the_view(const Scene& scene) {
  const double sharp = skinned_mean_red(render_skinned_frame(scene, 0));
  const double blurred = skinned_mean_red(render_skinned_frame(scene, 0, true));
  EXPECT_GT(blurred, sharp + 0.1);
  EXPECT_LT(blurred, 0.95);
}

TEST(SkinnedRender, AMovingJointBlursTheMeshOverTheShutter) {
  expect_blur_leaving_the_view(skinned_triangle(true, true));
}

// The joint's translation is linear in time: two steps (one segment) follow it exactly.
TEST(SkinnedRender, OnlyAMovingSkinBuildsMotionSteps) {
  const ShotTimes shutter{0, 0, 1};
  const Scene moving_scene = skinned_triangle(true, true);
  const RenderGeometry moving(moving_scene, Transform(), shutter, MotionTolerance{});
  EXPECT_EQ(moving.moving_instance_count(), 1u);
  EXPECT_EQ(moving.most_motion_steps(), 2u);
  const Scene still_scene = skinned_triangle(true, false);
  const RenderGeometry still(still_scene, Transform(), shutter, MotionTolerance{});
  EXPECT_EQ(still.moving_instance_count(), 0u);
  EXPECT_EQ(still.most_motion_steps(), 1u);
}

// The triangle of skinned_triangle bound to a joint at the origin that turns `degrees` about +Z
// from t = 0 to 1 (a rotation channel: slerp, so the angle grows linearly).
Scene turning_triangle(double degrees) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh =
      gltf.mesh({{-5, -5, 0}, {5, -5, 0}, {0, 5, 0}}, {0, 1, 2}, gltf.material({0.5f, 0.5f, 0.5f}));
  const int joint = gltf.node(GltfBuilder::Node{});
  gltf.skin_weights(node.mesh, 0, std::vector<uint16_t>(12, 0),
                    {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
  node.skin = gltf.skin({joint});
  const double half = degrees * std::numbers::pi / 360;
  gltf.animate(joint, "rotation", {0, 1},
               {0, 0, 0, 1, 0, 0, float(std::sin(half)), float(std::cos(half))});
  gltf.node(node);
  return test::import_built(gltf, "turning.gltf");
}

// A vertex at radius r turning by θ strays from the chord of a segment of n by r (1 - cos(θ/2n))
// at the segment's middle, the most along it: the fewest 2^k segments within the tolerance.
size_t turning_steps_closed_form(double radius_m, double degrees, double tolerance_m) {
  const double theta = degrees * std::numbers::pi / 180;
  size_t segments = 1;
  while (radius_m * (1 - std::cos(theta / (2.0 * double(segments)))) > tolerance_m &&
         segments < kMaxEvaluatedShapes - 1)
    segments *= 2;
  return segments + 1;
}

// A joint turning a quarter turn gets the steps the closed form asks for at a tolerance of 1 mm
// (65), a nearly still one (half a degree) two; between the steps the posed vertices stray from
// their closed-form arcs by at most the tolerance, at every one of 1000 times over the shutter.
TEST(SkinnedRender, AJointsStepsFollowItsMotionWithinTheTolerance) {
  constexpr double kToleranceM = 1e-3;
  const MotionTolerance tolerance{kToleranceM, 0};
  const ShotTimes shutter{0, 0, 1};
  const double far_radius = std::sqrt(50.0);  // the corners at (±5, -5)
  for (const double degrees : {90.0, 0.5}) {
    const Scene scene = turning_triangle(degrees);
    ASSERT_EQ(scene.deformations.size(), 1u);
    const DeformationSteps steps = deformation_steps(
        scene, scene.instances[0], scene.deformations[0], Transform(), shutter, tolerance);
    EXPECT_EQ(steps.times_s.size(), turning_steps_closed_form(far_radius, degrees, kToleranceM))
        << degrees << " degrees";
    const std::vector<Vec3f>& base = scene.meshes[scene.deformations[0].mesh].positions;
    double worst = 0;
    for (int i = 0; i <= 1000; ++i) {
      const double t = i / 1000.0;
      const double angle = degrees * std::numbers::pi / 180 * t;
      const size_t k =
          std::min(size_t(t * double(steps.times_s.size() - 1)), steps.times_s.size() - 2);
      const double f = (t - steps.times_s[k]) / (steps.times_s[k + 1] - steps.times_s[k]);
      for (size_t v = 0; v < base.size(); ++v) {
        const Vec3d exact{base[v].x * std::cos(angle) - base[v].y * std::sin(angle),
                          base[v].x * std::sin(angle) + base[v].y * std::cos(angle), base[v].z};
        const Vec3d drawn = Vec3d(steps.shapes[k].positions[v]) * (1 - f) +
                            Vec3d(steps.shapes[k + 1].positions[v]) * f;
        worst = std::max(worst, length(drawn - exact));
      }
    }
    EXPECT_LE(worst, kToleranceM) << degrees << " degrees";
    std::printf("a joint turning %g degrees: %zu steps, the drawn vertices at most %.3g m off\n",
                degrees, steps.times_s.size(), worst);
  }
}

TEST(SkinnedRender, StillJointsRenderTheUnskinnedImageBitForBit) {
  const Image plain = render_skinned_frame(skinned_triangle(false, false), 0);
  const Image skinned = render_skinned_frame(skinned_triangle(true, false), 0);
  ASSERT_EQ(plain.width, skinned.width);
  size_t differing = 0;
  for (uint32_t y = 0; y < plain.height; ++y)
    for (uint32_t x = 0; x < plain.width; ++x)
      for (uint32_t c = 0; c < 3; ++c)
        differing += plain.at(x, y, c) != skinned.at(x, y, c);
  EXPECT_EQ(differing, 0u);
  EXPECT_LT(skinned_mean_red(plain), 0.9);  // the triangle is in the picture
}

// A grey triangle filling the view of a camera 3 m up +Z at the frame (t = 0), and 10 m along
// +X, out of the view, at the `shapes` - 1 later times evenly spaced to t = 1 (`moving`; else in
// view at all). The file's base mesh is out of the view: only the shapes put it there. With
// `node_moves` the node's own translation carries the shapes 10 m along +X from t = 0 to 1.
Scene evaluated_triangle(bool moving, size_t shapes = 3, bool node_moves = false) {
  GltfBuilder gltf;
  const std::vector<Vec3f> in_view = {{-5, -5, 0}, {5, -5, 0}, {0, 5, 0}};
  std::vector<Vec3f> away = in_view;
  for (Vec3f& p : away)
    p.x += 10;
  GltfBuilder::Node node;
  node.mesh = gltf.mesh(away, {0, 1, 2}, gltf.material({0.5f, 0.5f, 0.5f}));
  const int n = gltf.node(node);
  if (node_moves) gltf.animate(n, "translation", {0, 1}, {0, 0, 0, 10, 0, 0});
  std::vector<double> times;
  std::vector<std::vector<Vec3f>> positions;
  for (size_t k = 0; k < shapes; ++k) {
    times.push_back(shapes > 1 ? double(k) / double(shapes - 1) : 0.0);
    positions.push_back(moving && k > 0 ? away : in_view);
  }
  gltf.evaluated_shapes(n, times, positions);
  GltfBuilder::Node camera;
  camera.camera = gltf.perspective_camera(0.5, 1.0, 0.1, 100);
  camera.translation = {0, 0, 3};
  gltf.node(camera);
  return test::import_built(gltf, "evaluated.gltf");
}

TEST(EvaluatedRender, TheFramesShapeIsWhatAClosedShutterShows) {
  // The grey triangle (albedo 0.5 under a sky of 1), not the base mesh out of the view.
  EXPECT_NEAR(skinned_mean_red(render_skinned_frame(evaluated_triangle(true), 0)), 0.5, 0.1);
}

TEST(EvaluatedRender, AnOpenShutterBlursOverTheShapes) {
  expect_blur_leaving_the_view(evaluated_triangle(true));
}

TEST(EvaluatedRender, MotionStepsAreTheFilesShapesAndStillShapesBuildNone) {
  const ShotTimes shutter{0, 0, 1};
  for (const size_t shapes : {3u, 9u, 129u}) {
    const Scene moving_scene = evaluated_triangle(true, shapes);
    const RenderGeometry moving(moving_scene, Transform(), shutter, MotionTolerance{});
    EXPECT_EQ(moving.moving_instance_count(), 1u);
    EXPECT_EQ(moving.most_motion_steps(), shapes);
    const RenderGeometry closed(moving_scene, Transform(), ShotTimes{}, MotionTolerance{});
    EXPECT_EQ(closed.most_motion_steps(), 1u);
  }
  const Scene still_scene = evaluated_triangle(false);
  const RenderGeometry still(still_scene, Transform(), shutter, MotionTolerance{});
  EXPECT_EQ(still.moving_instance_count(), 0u);
  EXPECT_EQ(still.most_motion_steps(), 1u);
}

// A file's shapes count in the memory estimate: 129 shapes of a 4096-vertex mesh (25 MB of
// shapes and motion steps) are refused under an 8 MiB limit before anything is built, where the
// same mesh with one shape renders.
// The node's rigid motion combines with the shapes: still shapes on a moving node blur, with the
// file's step count when it has several shapes and, when it has one, the steps the node's motion
// needs (a linear translation: two).
TEST(EvaluatedRender, AMovingNodeMovesItsShapes) {
  expect_blur_leaving_the_view(evaluated_triangle(false, 1, true));
  const ShotTimes shutter{0, 0, 1};
  for (const auto& [shapes, steps] : {std::pair<size_t, uint32_t>{1, 2}, {3, 3}}) {
    const Scene scene = evaluated_triangle(false, shapes, true);
    const RenderGeometry geometry(scene, Transform(), shutter, MotionTolerance{});
    EXPECT_EQ(geometry.moving_instance_count(), 1u);
    EXPECT_EQ(geometry.most_motion_steps(), steps) << shapes << " shapes";
  }
}

TEST(EvaluatedRender, ShapesBeyondTheMemoryLimitAreRefusedBeforeTheRender) {
  const auto many_vertices = [](size_t shapes) {
    GltfBuilder gltf;
    std::vector<Vec3f> soup;
    std::vector<uint32_t> indices;
    for (uint32_t v = 0; v < 4095; ++v) {
      soup.push_back({float(v % 3), float(v / 3) * 0.01f, -20.f});
      indices.push_back(v);
    }
    GltfBuilder::Node node;
    node.mesh = gltf.mesh(soup, indices, gltf.material({0.5f, 0.5f, 0.5f}));
    const int n = gltf.node(node);
    std::vector<double> times;
    std::vector<std::vector<Vec3f>> positions;
    for (size_t k = 0; k < shapes; ++k) {
      times.push_back(double(k));
      positions.push_back(soup);
      positions.back()[0].z += float(k);
    }
    gltf.evaluated_shapes(n, times, positions);
    return test::import_built(gltf, "evaluated_large.gltf");
  };
  RenderOptions options;
  options.width = 8, options.height = 8, options.samples_per_pixel = 1;
  options.shutter_s = Vec2d{0.0, 1.0};
  options.frame = 0, options.fps = 1;
  options.show_progress = false;
  options.memory_limit_bytes = 8u << 20;
  EXPECT_NO_THROW(RenderJob(many_vertices(1), options, test::loader()).run());
  try {
    RenderJob(many_vertices(kMaxEvaluatedShapes), options, test::loader()).run();
    ADD_FAILURE() << "129 shapes rendered under an 8 MiB limit";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more than the memory limit"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace fb
