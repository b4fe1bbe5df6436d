// Blender's Vector pass (--passes Vector; core/render/motion_vectors.h) on shots whose motion is
// known in pixels: a quad keyed to move 4 px right and 2 px up per frame under an orthographic
// camera, a camera travelling past a still quad, a quad turning in the image plane, whose
// vectors grow with the distance from its centre, a quad a morph target stretches and one a
// skin's joint carries.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>

#include "core/render/render_job.h"
#include "core/util/error.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

// 32 x 24 pixels, 0.1 m each under the orthographic camera (glTF's xmag and ymag are half the
// view); the shot is frame 12 at 24 fps (t = 0.5 s), its keys at t = 0 and 1 s.
constexpr uint32_t kVectorWidthPx = 32, kVectorHeightPx = 24;
constexpr double kVectorMetresPerPx = 0.1;
constexpr double kVectorFrame = 12, kVectorFps = 24;
// Cycles' vectors agree to 0.01 px (issue 20).
constexpr float kVectorTolerancePx = 0.01f;

const std::vector<uint32_t> kVectorSquare = {0, 1, 2, 0, 2, 3};

// A square of `side` metres centred on its node's origin, facing +z.
std::vector<Vec3f> vector_square(double side) {
  const float h = float(side / 2);
  return {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}};
}

RenderOptions vector_options() {
  RenderOptions options;
  options.width = kVectorWidthPx, options.height = kVectorHeightPx;
  options.samples_per_pixel = 16;
  options.filter = "box";
  options.integrator = "path:max_depth=0";
  options.frame = kVectorFrame, options.fps = kVectorFps;
  options.show_progress = false;
  options.passes = {"Vector"};
  return options;
}

// The pixel's X, Y, Z, W.
std::array<float, 4> vector_at(const Image& image, uint32_t x, uint32_t y) {
  const auto first = std::find(image.channels.begin(), image.channels.end(), "ViewLayer.Vector.X");
  EXPECT_NE(first, image.channels.end());
  const size_t c = size_t(first - image.channels.begin());
  EXPECT_EQ(image.channels[c + 3], "ViewLayer.Vector.W");
  return {image.at(x, y, c), image.at(x, y, c + 1), image.at(x, y, c + 2), image.at(x, y, c + 3)};
}

// What share of pixel (x, y) the axis-aligned rectangle [x0, x1) x [y0, y1) (pixels) covers.
double pixel_share(uint32_t x, uint32_t y, double x0, double y0, double x1, double y1) {
  const auto span = [](uint32_t i, double lo, double hi) {
    return std::clamp(std::min(hi, i + 1.0) - std::max(lo, double(i)), 0.0, 1.0);
  };
  return span(x, x0, x1) * span(y, y0, y1);
}

// A 1 m quad (10 px) 5 m in front of the orthographic camera, its centre keyed linearly from
// `at_0` (t = 0) to `at_1` (t = 1 s), metres in the image plane (x right, y up).
Scene sliding_quad_scene(std::array<float, 2> at_0, std::array<float, 2> at_1) {
  GltfBuilder gltf;
  GltfBuilder::Node quad, camera;
  quad.mesh = gltf.mesh(vector_square(1.0), kVectorSquare, gltf.material({0.5f, 0.5f, 0.5f}));
  camera.camera = gltf.orthographic_camera(kVectorWidthPx * kVectorMetresPerPx / 2,
                                           kVectorHeightPx * kVectorMetresPerPx / 2, 0.1, 100);
  const int q = gltf.node(quad);
  gltf.node(camera);
  gltf.animate(q, "translation", {0, 1}, {at_0[0], at_0[1], -5, at_1[0], at_1[1], -5});
  return test::import_built(gltf, "sliding_quad.gltf");
}

TEST(MotionVectorRender, QuadMovingAKnownSpeedHasItsVectorOnEveryPixelItTouches) {
  // 4 px right and 2 px up per frame, through the image's centre at frame 12.
  const float dx_m = float(4 * kVectorMetresPerPx * kVectorFps),
              dy_m = float(2 * kVectorMetresPerPx * kVectorFps);
  const Scene scene = sliding_quad_scene({-dx_m / 2, -dy_m / 2}, {dx_m / 2, dy_m / 2});
  const Image image = RenderJob(scene, vector_options(), test::loader()).run().image;
  // The quad covers pixels [11, 21) x [7, 17) at the frame.
  const double x0 = kVectorWidthPx / 2.0 - 5, y0 = kVectorHeightPx / 2.0 - 5;
  size_t on_quad = 0;
  for (uint32_t y = 0; y < kVectorHeightPx; ++y)
    for (uint32_t x = 0; x < kVectorWidthPx; ++x) {
      const std::array<float, 4> v = vector_at(image, x, y);
      // Cycles' convention (docs/blender.md): previous minus current, current minus next, y up.
      const std::array<float, 4> expected = pixel_share(x, y, x0, y0, x0 + 10, y0 + 10) > 0
                                                ? std::array{-4.f, -2.f, -4.f, -2.f}
                                                : std::array{0.f, 0.f, 0.f, 0.f};
      on_quad += expected[0] != 0;
      for (size_t c = 0; c < 4; ++c)
        EXPECT_NEAR(v[c], expected[c], kVectorTolerancePx)
            << "channel " << c << " at " << x << "," << y;
    }
  EXPECT_EQ(on_quad, 100u);
}

TEST(MotionVectorRender, ARenderWithoutVectorIsTheSameAndOneWithItOnlyAddsTheChannels) {
  const Scene scene = sliding_quad_scene({-1, 0}, {1, 0});
  RenderOptions depth_only = vector_options();
  depth_only.passes = {"Depth"};
  RenderOptions with_vector = vector_options();
  with_vector.passes = {"Depth", "Vector"};
  const Image without = RenderJob(scene, depth_only, test::loader()).run().image;
  const Image with = RenderJob(scene, with_vector, test::loader()).run().image;
  ASSERT_EQ(with.channels.size(), without.channels.size() + 4);
  for (uint32_t y = 0; y < kVectorHeightPx; ++y)
    for (uint32_t x = 0; x < kVectorWidthPx; ++x)
      for (size_t c = 0; c < without.channels.size(); ++c) {
        ASSERT_EQ(with.channels[c], without.channels[c]);
        ASSERT_EQ(std::bit_cast<uint32_t>(with.at(x, y, c)),
                  std::bit_cast<uint32_t>(without.at(x, y, c)))
            << with.channels[c] << " " << x << "," << y;
      }
}

TEST(MotionVectorRender, CameraTravellingPastAStillQuadMovesItTheOtherWay) {
  // A perspective camera with glTF's yfov = 2 atan(0.1) on a 32 x 24 image: f = 12 / 0.1 = 120 px
  // per unit of depth; the quad 10 m away, so 12 px per metre there. The camera travels +x by
  // 0.25 m per frame: the quad moves 3 px left per frame in the image.
  constexpr double kFocalPx = 120, kDepthM = 10, kStepM = 0.25;
  GltfBuilder gltf;
  GltfBuilder::Node quad, camera;
  quad.mesh = gltf.mesh(vector_square(1.0), kVectorSquare, gltf.material({0.5f, 0.5f, 0.5f}));
  quad.translation = {0, 0, -kDepthM};
  camera.camera = gltf.perspective_camera(2 * std::atan(0.1),
                                          double(kVectorWidthPx) / kVectorHeightPx, 0.1, 100);
  gltf.node(quad);
  const int c = gltf.node(camera);
  const float half = float(kStepM * kVectorFps / 2);
  gltf.animate(c, "translation", {0, 1}, {-half, 0, 0, half, 0, 0});
  const Scene scene = test::import_built(gltf, "travelling_camera.gltf");
  const Image image = RenderJob(scene, vector_options(), test::loader()).run().image;
  const float shift_px = float(kStepM * kFocalPx / kDepthM);
  const double side_px = kFocalPx / kDepthM;  // the quad's side: 12 px
  const double x0 = kVectorWidthPx / 2.0 - side_px / 2, y0 = kVectorHeightPx / 2.0 - side_px / 2;
  for (uint32_t y = 0; y < kVectorHeightPx; ++y)
    for (uint32_t x = 0; x < kVectorWidthPx; ++x) {
      const std::array<float, 4> v = vector_at(image, x, y);
      const bool hit = pixel_share(x, y, x0, y0, x0 + side_px, y0 + side_px) > 0;
      // The camera was left of here a frame ago: the quad stood further right, so previous minus
      // current is +shift; it will stand further left, so current minus next is +shift too.
      const std::array<float, 4> expected =
          hit ? std::array{shift_px, 0.f, shift_px, 0.f} : std::array{0.f, 0.f, 0.f, 0.f};
      for (size_t k = 0; k < 4; ++k)
        EXPECT_NEAR(v[k], expected[k], kVectorTolerancePx)
            << "channel " << k << " at " << x << "," << y;
    }
}

TEST(MotionVectorRender, TurningQuadsVectorsGrowWithTheDistanceFromItsCentre) {
  // A 1.6 m quad (16 px) facing the orthographic camera, turning about the view axis by 0.05 rad
  // per frame (keys at +-0.6 rad about frame 12, slerp: a constant angular speed).
  constexpr double kTurnPerFrameRad = 0.05, kSidePx = 16;
  GltfBuilder gltf;
  GltfBuilder::Node quad, camera;
  quad.mesh = gltf.mesh(vector_square(kSidePx * kVectorMetresPerPx), kVectorSquare,
                        gltf.material({0.5f, 0.5f, 0.5f}));
  quad.translation = {0, 0, -5};
  camera.camera = gltf.orthographic_camera(kVectorWidthPx * kVectorMetresPerPx / 2,
                                           kVectorHeightPx * kVectorMetresPerPx / 2, 0.1, 100);
  const int q = gltf.node(quad);
  gltf.node(camera);
  const float half_angle = float(kTurnPerFrameRad * kVectorFrame / 2);
  gltf.animate(q, "rotation", {0, 1},
               {0, 0, -std::sin(half_angle), std::cos(half_angle), 0, 0, std::sin(half_angle),
                std::cos(half_angle)});
  const Scene scene = test::import_built(gltf, "turning_quad.gltf");
  RenderOptions options = vector_options();
  options.samples_per_pixel = 64;  // the mean sample position within 0.01 px of the centre
  const Image image = RenderJob(scene, options, test::loader()).run().image;
  // Inside the quad's circle of radius 8 px, whatever its angle: each pixel is wholly covered at
  // every sample. The vector is linear in the point, so the pixel's mean is its centre's.
  const double cx = kVectorWidthPx / 2.0, cy = kVectorHeightPx / 2.0;
  const double c = std::cos(kTurnPerFrameRad), s = std::sin(kTurnPerFrameRad);
  float largest = 0;
  size_t checked = 0;
  for (uint32_t y = 0; y < kVectorHeightPx; ++y)
    for (uint32_t x = 0; x < kVectorWidthPx; ++x) {
      const double u = x + 0.5 - cx, v = cy - (y + 0.5);  // y up, from the centre
      if (std::hypot(std::abs(u) + 0.5, std::abs(v) + 0.5) > kSidePx / 2) continue;
      // A frame ago it stood turned back by the step, a frame on turned on by it.
      const double previous_u = c * u + s * v, previous_v = -s * u + c * v;
      const double next_u = c * u - s * v, next_v = s * u + c * v;
      const std::array<float, 4> expected = {float(previous_u - u), float(previous_v - v),
                                             float(u - next_u), float(v - next_v)};
      const std::array<float, 4> got = vector_at(image, x, y);
      for (size_t k = 0; k < 4; ++k)
        EXPECT_NEAR(got[k], expected[k], kVectorTolerancePx)
            << "channel " << k << " at " << x << "," << y;
      largest = std::max(largest, std::hypot(got[0], got[1]));
      ++checked;
    }
  EXPECT_GT(checked, 100u);
  EXPECT_GT(largest, 0.3f);  // the outer pixels move by 0.05 x 7 px
}

TEST(MotionVectorRender, MorphedQuadsPointsFollowTheirTriangles) {
  // A 1 m quad whose morph target takes its right edge 2.4 m (24 px) further right, its weight
  // keyed from 0 (t = 0) to 1 (t = 1 s): the right edge moves 1 px per frame, the left one not at
  // all, and a point between them by its share of the way (the displacement is linear across
  // each triangle). At frame 12 the quad spans 22 px, from column 5 to 26.
  constexpr double kRestSideM = 1, kStretchM = 2.4;
  GltfBuilder gltf;
  GltfBuilder::Node quad, camera;
  quad.mesh =
      gltf.mesh(vector_square(kRestSideM), kVectorSquare, gltf.material({0.5f, 0.5f, 0.5f}));
  const Vec3f stretch{float(kStretchM), 0, 0}, still{0, 0, 0};
  gltf.morph_target(quad.mesh, {still, stretch, stretch, still});
  constexpr double kQuadXM = -0.6;  // the stretched quad centred at frame 12
  quad.translation = {kQuadXM, 0, -5};
  camera.camera = gltf.orthographic_camera(kVectorWidthPx * kVectorMetresPerPx / 2,
                                           kVectorHeightPx * kVectorMetresPerPx / 2, 0.1, 100);
  const int q = gltf.node(quad);
  gltf.node(camera);
  gltf.animate(q, "weights", {0, 1}, {0, 1});
  const Scene scene = test::import_built(gltf, "morphed_quad.gltf");
  const Image image = RenderJob(scene, vector_options(), test::loader()).run().image;
  const double left_px = kVectorWidthPx / 2.0 + (kQuadXM - kRestSideM / 2) / kVectorMetresPerPx;
  const double width_px = (kRestSideM + kStretchM / 2) / kVectorMetresPerPx;
  const double per_frame_px = kStretchM / kVectorMetresPerPx / (kVectorFps * 1.0);
  const double top_px = kVectorHeightPx / 2.0 - kRestSideM / 2 / kVectorMetresPerPx;
  size_t checked = 0;
  for (uint32_t y = 0; y < kVectorHeightPx; ++y)
    for (uint32_t x = 0; x < kVectorWidthPx; ++x) {
      const std::array<float, 4> v = vector_at(image, x, y);
      const double share = pixel_share(x, y, left_px, top_px, left_px + width_px,
                                       top_px + kRestSideM / kVectorMetresPerPx);
      if (share == 0) {
        for (size_t k = 0; k < 4; ++k)
          EXPECT_EQ(v[k], 0.f) << "channel " << k << " at " << x << "," << y;
        continue;
      }
      if (share < 1) continue;  // an edge pixel: the mean of its hits only
      // The pixel's mean over its samples is its centre's value: the motion is linear in x.
      const float expected = float(-per_frame_px * (x + 0.5 - left_px) / width_px);
      EXPECT_NEAR(v[0], expected, kVectorTolerancePx) << x << "," << y;
      EXPECT_NEAR(v[2], expected, kVectorTolerancePx) << x << "," << y;
      EXPECT_NEAR(v[1], 0.f, kVectorTolerancePx) << x << "," << y;
      EXPECT_NEAR(v[3], 0.f, kVectorTolerancePx) << x << "," << y;
      ++checked;
    }
  EXPECT_EQ(checked, 220u);  // 22 whole columns of 10 rows
}

TEST(MotionVectorRender, SkinnedQuadMovesWithItsJoint) {
  // A 1 m quad bound to one joint (its node's own placement is ignored, as glTF says) that
  // travels 3 px left per frame 5 m in front of the orthographic camera.
  GltfBuilder gltf;
  GltfBuilder::Node joint, quad, camera;
  const int joint_node = gltf.node(joint);
  quad.mesh = gltf.mesh(vector_square(1.0), kVectorSquare, gltf.material({0.5f, 0.5f, 0.5f}));
  gltf.skin_weights(quad.mesh, 0, std::vector<uint16_t>(16, 0),
                    {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
  quad.skin = gltf.skin({joint_node});
  gltf.node(quad);
  camera.camera = gltf.orthographic_camera(kVectorWidthPx * kVectorMetresPerPx / 2,
                                           kVectorHeightPx * kVectorMetresPerPx / 2, 0.1, 100);
  gltf.node(camera);
  const float half = float(3 * kVectorMetresPerPx * kVectorFps / 2);
  gltf.animate(joint_node, "translation", {0, 1}, {half, 0, -5, -half, 0, -5});
  const Scene scene = test::import_built(gltf, "skinned_quad.gltf");
  const Image image = RenderJob(scene, vector_options(), test::loader()).run().image;
  const double x0 = kVectorWidthPx / 2.0 - 5, y0 = kVectorHeightPx / 2.0 - 5;
  for (uint32_t y = 0; y < kVectorHeightPx; ++y)
    for (uint32_t x = 0; x < kVectorWidthPx; ++x) {
      const std::array<float, 4> v = vector_at(image, x, y);
      const std::array<float, 4> expected = pixel_share(x, y, x0, y0, x0 + 10, y0 + 10) > 0
                                                ? std::array{3.f, 0.f, 3.f, 0.f}
                                                : std::array{0.f, 0.f, 0.f, 0.f};
      for (size_t k = 0; k < 4; ++k)
        EXPECT_NEAR(v[k], expected[k], kVectorTolerancePx)
            << "channel " << k << " at " << x << "," << y;
    }
}

TEST(MotionVectorRender, APanoramicCameraIsAUsageError) {
  const Scene scene = sliding_quad_scene({-1, 0}, {1, 0});
  RenderOptions options = vector_options();
  options.camera_model = "equirectangular";
  EXPECT_THROW((void)RenderJob(scene, options, test::loader()), UsageError);
}

}  // namespace
}  // namespace fb
