// Motion blur against closed forms (issue 3, "Evidence"): an emitter moving at a known speed
// streaks over exactly its projected travel during the shutter; a camera moving past a still one
// does the same; a turning arm draws an arc, not a chord; a scene where nothing moves renders
// bit-identically with the shutter open or closed.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/render/render_job.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

// A 96 x 24 frame with glTF's yfov = 2 atan(0.1) and the same aspect ratio: by glTF's definition
// of yfov, f = (24 / 2) / 0.1 = 120 px per unit of depth on both axes, centre (48, 12).
constexpr uint32_t kStreakWidth = 96, kStreakHeight = 24;
constexpr double kFocalPx = 120, kCentreX = 48;
constexpr double kDepth = 10;                        // m, of the marker's plane
constexpr double kMarkerPx = 4, kMarkerTallPx = 16;  // the marker's width and height in the image
// Sampling noise at 1024 spp, measured over seeds 0-9: sigma 0.07 px on a streak's length and
// 0.04 px on its centroid; the centroid limit is 5 sigma.
constexpr double kCentroidLimitPx = 0.2;
constexpr double kTravelPx = 40.3;  // during the shutter
constexpr double kShutterOpenS = -0.1, kShutterCloseS = 0.1;
constexpr double kFrame = 12, kFps = 24;  // t = 0.5 s
constexpr double kMetresPerPx = kDepth / kFocalPx;
constexpr double kSpeed = kTravelPx * kMetresPerPx / (kShutterCloseS - kShutterOpenS);  // m/s

const std::vector<uint32_t> kSquare = {0, 1, 2, 0, 2, 3};

std::vector<Vec3f> rectangle(double width, double height) {
  const float w = float(width / 2), h = float(height / 2);
  return {{-w, -h, 0}, {w, -h, 0}, {w, h, 0}, {-w, h, 0}};
}
std::vector<Vec3f> square(double side) {
  return rectangle(side, side);
}

RenderOptions streak_options() {
  RenderOptions options;
  options.width = kStreakWidth, options.height = kStreakHeight, options.samples_per_pixel = 1024;
  options.filter = "box";  // each pixel the plain mean over its square
  options.integrator = "path:max_depth=0";
  options.shutter_s = Vec2d{kShutterOpenS, kShutterCloseS};
  options.frame = kFrame, options.fps = kFps;
  options.show_progress = false;
  return options;
}

Image render_motion_shot(const Scene& scene, const RenderOptions& options,
                         std::string* plan = nullptr) {
  const RenderJob job(scene, options, test::loader());
  if (plan) *plan = job.plan();
  return job.run().image;
}

// The marker (radiance 1) at depth kDepth; `marker_moves`: it travels along +X at kSpeed,
// through x = 0 at the frame's time; else the camera travels so.
Scene streak_scene(bool marker_moves) {
  GltfBuilder gltf;
  GltfBuilder::Node marker, camera;
  marker.mesh = gltf.mesh(rectangle(kMarkerPx * kMetresPerPx, kMarkerTallPx * kMetresPerPx),
                          kSquare, gltf.material({0, 0, 0}, {1, 1, 1}, 1.0, true));
  marker.translation = {0, 0, -kDepth};
  camera.camera =
      gltf.perspective_camera(2 * std::atan(0.1), double(kStreakWidth) / kStreakHeight, 0.1, 100);
  const int m = gltf.node(marker), c = gltf.node(camera);
  const float half = float(kSpeed / 2);  // keys at t = 0 and 1 s, the frame at 0.5 s
  if (marker_moves)
    gltf.animate(m, "translation", {0, 1}, {-half, 0, float(-kDepth), half, 0, float(-kDepth)});
  else
    gltf.animate(c, "translation", {0, 1}, {-half, 0, 0, half, 0, 0});
  return test::import_built(gltf, marker_moves ? "moving_marker.gltf" : "moving_camera.gltf");
}

std::vector<double> column_sums(const Image& image) {
  std::vector<double> sums(image.width, 0.0);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      sums[x] += image.at(x, y, 1);
  return sums;
}

struct Streak {
  double left_px, right_px;  // where the profile crosses half its plateau
  double centroid_px;
};

// A rectangle of width w moving by L > w blurs into a trapezoid: ramps of width w, a plateau, and
// half-plateau crossings exactly where the square's centre was at shutter open and close. Pixel
// centres on a ramp (w >= 3 px) sample it exactly, so linear interpolation finds the crossings.
Streak measure(const std::vector<double>& p) {
  const double top = *std::max_element(p.begin(), p.end());
  double plateau = 0;
  int n = 0;
  for (double v : p)
    if (v > 0.8 * top) plateau += v, ++n;
  const double half = plateau / n / 2;
  Streak s{};
  size_t i = 0;
  while (p[i] < half)
    ++i;
  s.left_px = (i - 0.5) + (half - p[i - 1]) / (p[i] - p[i - 1]);
  size_t j = p.size() - 1;
  while (p[j] < half)
    --j;
  s.right_px = (j + 0.5) + (p[j] - half) / (p[j] - p[j + 1]);
  double sum = 0, moment = 0;
  for (size_t x = 0; x < p.size(); ++x)
    sum += p[x], moment += p[x] * (x + 0.5);
  s.centroid_px = moment / sum;
  return s;
}

TEST(MotionBlur, MovingEmitterStreaksOverItsProjectedTravel) {
  const Scene scene = streak_scene(true);
  std::string plan;
  const Streak s = measure(column_sums(render_motion_shot(scene, streak_options(), &plan)));
  EXPECT_NE(plan.find("time samples for 1 moving instance"), std::string::npos) << plan;
  std::printf(
      "moving marker: streak %.4f px (expected %.4f), from %.4f to %.4f px (expected "
      "%.4f to %.4f), centroid %.4f px\n",
      s.right_px - s.left_px, kTravelPx, s.left_px, s.right_px, kCentreX - kTravelPx / 2,
      kCentreX + kTravelPx / 2, s.centroid_px);
  EXPECT_NEAR(s.right_px - s.left_px, kTravelPx, 0.5);
  EXPECT_NEAR(s.left_px, kCentreX - kTravelPx / 2, 0.5);
  EXPECT_NEAR(s.right_px, kCentreX + kTravelPx / 2, 0.5);
  EXPECT_NEAR(s.centroid_px, kCentreX, kCentroidLimitPx);  // a box shutter: every moment alike
}

TEST(MotionBlur, ShutterCurveWeighsTheStreak) {
  // Exposure rising linearly from open to close: the mean time is 2/3 of the way, so the
  // centroid sits at open + 2L/3, L/6 right of the centre; the streak's ends stay put.
  RenderOptions options = streak_options();
  options.shutter_curve = "table:values=[0,1]";
  const Image image = render_motion_shot(streak_scene(true), options);
  const Streak s = measure(column_sums(image));
  std::printf("rising shutter: centroid %.4f px (expected %.4f)\n", s.centroid_px,
              kCentreX + kTravelPx / 6);
  EXPECT_NEAR(s.centroid_px, kCentreX + kTravelPx / 6, kCentroidLimitPx);
  // The profile's plateau is no longer flat: it rises as the exposure does.
  const std::vector<double> p = column_sums(image);
  EXPECT_GT(p[size_t(kCentreX + kTravelPx / 4)], 1.5 * p[size_t(kCentreX - kTravelPx / 4)]);
}

TEST(MotionBlur, MovingCameraStreaksAStillEmitter) {
  const Scene scene = streak_scene(false);
  std::string plan;
  const Streak s = measure(column_sums(render_motion_shot(scene, streak_options(), &plan)));
  EXPECT_NE(plan.find("the moving camera"), std::string::npos) << plan;
  std::printf("moving camera: streak %.4f px (expected %.4f), centroid %.4f px\n",
              s.right_px - s.left_px, kTravelPx, s.centroid_px);
  EXPECT_NEAR(s.right_px - s.left_px, kTravelPx, 0.5);
  EXPECT_NEAR(s.centroid_px, kCentreX, kCentroidLimitPx);
}

TEST(MotionBlur, MovingSceneIsBitIdenticalForAnyThreadCount) {
  const Scene scene = streak_scene(true);
  RenderOptions options = streak_options();
  options.samples_per_pixel = 16;
  std::vector<float> pixels[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    pixels[threads - 1] = render_motion_shot(scene, options).pixels;
  }
  EXPECT_EQ(pixels[0], pixels[1]);
}

// An arm turning at a constant rate carries the marker along an arc: its time-averaged centroid
// lies at R sin(a/2) / (a/2) from the pivot for a turn a during the shutter, where linear motion
// between the shutter's ends would put it at R cos(a/2). Only enough motion steps get it right.
TEST(MotionBlur, TurningArmDrawsAnArc) {
  constexpr uint32_t kSize = 64;
  constexpr double kFocal = 160;  // (64 / 2) / tan(yfov / 2) with tan(yfov / 2) = 0.2
  constexpr double kArmM = 1.5, kTurnRad = 1.5, kRate = kTurnRad / 0.6;  // shutter 0.6 s
  GltfBuilder gltf;
  GltfBuilder::Node pivot, marker, camera;
  marker.mesh = gltf.mesh(square(0.15), kSquare, gltf.material({0, 0, 0}, {1, 1, 1}, 1.0, true));
  marker.translation = {kArmM, 0, 0};
  pivot.translation = {0, 0, -kDepth};
  pivot.children = {gltf.node(marker, false)};
  camera.camera = gltf.perspective_camera(2 * std::atan(0.2), 1.0, 0.1, 100);
  const int p = gltf.node(pivot);
  gltf.node(camera);
  // About +Z, from -rate/2 rad at t = 0 to +rate/2 at t = 1: 0 at the frame's time, 0.5 s.
  const float h = float(kRate / 4);
  gltf.animate(p, "rotation", {0, 1},
               {0, 0, -std::sin(h), std::cos(h), 0, 0, std::sin(h), std::cos(h)});
  const Scene scene = test::import_built(gltf, "arm.gltf");
  RenderOptions options = streak_options();
  options.width = options.height = kSize;
  options.shutter_s = Vec2d{-0.3, 0.3};
  std::string plan;
  const Image image = render_motion_shot(scene, options, &plan);
  double sum = 0, mx = 0, my = 0;
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const double v = image.at(x, y, 1);
      sum += v, mx += v * (x + 0.5), my += v * (y + 0.5);
    }
  const double arc = kArmM * std::sin(kTurnRad / 2) / (kTurnRad / 2) * kFocal / kDepth;
  const double chord = kArmM * std::cos(kTurnRad / 2) * kFocal / kDepth;
  std::printf("turning arm: centroid %.4f px from the pivot (arc %.4f, chord %.4f), %s\n",
              mx / sum - kSize / 2.0, arc, chord, plan.substr(plan.find("time samples")).c_str());
  EXPECT_NEAR(mx / sum - kSize / 2.0, arc, kCentroidLimitPx);
  EXPECT_NEAR(my / sum, kSize / 2.0, kCentroidLimitPx);
}

// The importer keeps each channel's interpolation and node: a STEP translation on a parent and a
// CUBICSPLINE rotation (zero tangents) on its child, a camera. At t = 1 s the parent has jumped
// to its second key and the child is halfway between its rotations, about +Y by 0.5 rad.
TEST(GltfAnimation, ChannelsBecomeCurvesOnTheirNodes) {
  GltfBuilder gltf;
  GltfBuilder::Node parent, child;
  child.camera = gltf.perspective_camera(0.8, 1.0, 0.1, 100);
  parent.mesh = gltf.mesh(square(1), kSquare, gltf.material({0.5f, 0.5f, 0.5f}));
  parent.children = {gltf.node(child, false)};
  const int p = gltf.node(parent);
  gltf.animate(p, "translation", {0, 1}, {0, 0, 0, 1, 2, 3}, "STEP");
  const float s = std::sin(0.5f), c = std::cos(0.5f);
  gltf.animate(parent.children[0], "rotation", {0, 2}, {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0,  //
                                                        0, 0, 0, 0, 0, s, 0, c, 0, 0, 0, 0},
               "CUBICSPLINE");
  const Scene scene = test::import_built(gltf, "channels.gltf");
  ASSERT_EQ(scene.hierarchy.curves.size(), 2u);
  EXPECT_EQ(scene.hierarchy.curves[0].interpolation, Interpolation::kStep);
  EXPECT_EQ(scene.hierarchy.curves[1].interpolation, Interpolation::kCubicSpline);
  EXPECT_EQ(scene.instances[0].node_index, scene.hierarchy.curves[0].node);
  EXPECT_EQ(scene.cameras[0].node_index, scene.hierarchy.curves[1].node);
  const Transform camera = scene.world_from_camera(scene.cameras[0], 1.0);
  const Vec3d position = camera.point({0, 0, 0}), forward = camera.vector({0, 0, -1});
  EXPECT_NEAR(position.x, 1, 1e-12);
  EXPECT_NEAR(position.y, 2, 1e-12);
  EXPECT_NEAR(position.z, 3, 1e-12);
  EXPECT_NEAR(forward.x, -std::sin(0.5), 1e-7);  // the keys are floats in the file
  EXPECT_NEAR(forward.z, -std::cos(0.5), 1e-7);
  EXPECT_EQ(scene.world_from_object(scene.instances[0], 0.999).point({0, 0, 0}).x, 0);
  EXPECT_TRUE(scene.moves(scene.instances[0].node_index, 0.9, 1.1));
  EXPECT_FALSE(scene.moves(scene.instances[0].node_index, 0.1, 0.9));
  EXPECT_TRUE(scene.moves(scene.cameras[0].node_index, 0.1, 0.9));  // its parent is still
}

TEST(GltfAnimation, StaticFilesKeepNoHierarchy) {
  GltfBuilder gltf;
  GltfBuilder::Node node;
  node.mesh = gltf.mesh(square(1), kSquare, gltf.material({0.5f, 0.5f, 0.5f}));
  gltf.node(node);
  const Scene scene = test::import_built(gltf, "static.gltf");
  EXPECT_TRUE(scene.hierarchy.nodes.empty());
  EXPECT_EQ(scene.instances[0].node_index, kNoNode);
}

// Nothing moves within the shutter: no time is drawn, so the open shutter changes no pixel.
TEST(MotionBlur, OpenShutterOnAStillSceneChangesNoPixel) {
  GltfBuilder gltf;
  GltfBuilder::Node floor, lamp, light, camera;
  floor.mesh = gltf.mesh(square(6), kSquare, gltf.material({0.7f, 0.6f, 0.5f}));
  floor.rotation = {-std::sin(0.7854), 0, 0, std::cos(0.7854)};
  lamp.mesh = gltf.mesh(square(1), kSquare, gltf.material({0, 0, 0}, {4, 4, 4}));
  lamp.translation = {0, 2, 0};
  lamp.rotation = {std::sin(0.7854), 0, 0, std::cos(0.7854)};
  light.light = gltf.point_light({1, 0.8f, 0.6f}, 683.0);
  light.translation = {1, 1, 1};
  camera.camera = gltf.perspective_camera(0.9, 1.5, 0.1, 100);
  camera.translation = {0, 1, 6};
  gltf.node(floor), gltf.node(light), gltf.node(camera);
  const int l = gltf.node(lamp);
  // The lamp is animated, but only after t = 2 s: still within any shutter near t = 0.
  gltf.animate(l, "translation", {2, 3}, {0, 2, 0, 0, 3, 0});
  const Scene scene = test::import_built(gltf, "still.gltf");
  RenderOptions options;
  options.width = 48, options.height = 32, options.samples_per_pixel = 8, options.seed = 5;
  options.show_progress = false;
  std::string plan;
  const std::vector<float> closed = render_motion_shot(scene, options).pixels;
  for (const Vec2d shutter : {Vec2d{0, 1.0 / 48}, Vec2d{-0.5, 0.5}}) {
    options.shutter_s = shutter;
    EXPECT_EQ(render_motion_shot(scene, options, &plan).pixels, closed)
        << shutter.x << "," << shutter.y;
    EXPECT_NE(plan.find("nothing moves in it: no time samples"), std::string::npos) << plan;
  }
  // Once the shutter reaches the animation, the lamp moves and time is sampled.
  options.shutter_s = Vec2d{1.5, 2.5};
  render_motion_shot(scene, options, &plan);
  EXPECT_NE(plan.find("time samples for 1 moving instance"), std::string::npos) << plan;
}

}  // namespace
}  // namespace fb
