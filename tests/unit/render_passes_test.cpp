// Render passes (--passes, filmback/render_passes.h) checked against their meaning on scenes whose
// answer is known: the depth of a plane, the normals of a sphere, the diffuse colour of a textured
// wall, the diffuse and glossy weights of a ball; and the beauty of a render with passes bit for
// bit that of one without.
#include <gtest/gtest.h>

#include <filmback/render_passes.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/render/render_job.h"
#include "support/albedo_checker.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"
#include "support/textured_quad.h"

namespace fb {
namespace {

constexpr uint32_t kPassImagePx = 40;

size_t channel_index(const Image& image, const std::string& name) {
  const auto it = std::find(image.channels.begin(), image.channels.end(), name);
  EXPECT_NE(it, image.channels.end()) << name;
  return size_t(it - image.channels.begin());
}

// A ball of radius 1 m, 5 m in front of a pinhole at the origin looking down -z (35 mm lens on a
// 36 mm wide sensor), under a uniform grey world.
constexpr double kPassBallRadius = 1, kPassFocalMm = 35, kPassSensorMm = 36;
constexpr Vec3d kPassBallCentre{0.4, -0.3, -5};

Scene ball_scene(Rgb emission) {
  Scene scene;
  Material material;
  material.base_color = {0.8f, 0.5f, 0.25f};
  material.emission = emission;
  scene.materials.push_back(material);
  Solid ball;
  ball.kind = SolidKind::kSphere;
  ball.name = "ball";
  ball.world_from_object = Transform::translate(kPassBallCentre) *
                           Transform::scale({kPassBallRadius, kPassBallRadius, kPassBallRadius});
  scene.solids.push_back(ball);
  SceneCamera camera;
  camera.name = "camera";
  camera.physical.focal_length_mm = kPassFocalMm;
  camera.physical.sensor_width_mm = kPassSensorMm;
  scene.cameras.push_back(camera);
  scene.background = {0.5f, 0.5f, 0.5f};
  return scene;
}

RenderOptions ball_options(uint32_t spp, const char* filter) {
  RenderOptions options;
  options.width = kPassImagePx, options.height = kPassImagePx, options.samples_per_pixel = spp;
  options.filter = filter;
  options.show_progress = false;
  return options;
}

// The pinhole's unit ray through raster position (px, py).
Vec3d ball_ray(double px, double py) {
  const double pixel_mm = kPassSensorMm / kPassImagePx;
  return normalize(Vec3d{(px - kPassImagePx / 2.0) * pixel_mm,
                         -(py - kPassImagePx / 2.0) * pixel_mm, -kPassFocalMm});
}

// How far pixel (x, y)'s central ray points from the ball's centre, as a share of the ball's
// angular radius: below 1 the ray hits it.
double ball_off_centre(uint32_t x, uint32_t y) {
  const Vec3d d = ball_ray(x + 0.5, y + 0.5);
  return std::acos(std::min(1.0, dot(d, normalize(kPassBallCentre)))) /
         std::asin(kPassBallRadius / length(kPassBallCentre));
}

TEST(RenderPasses, DepthOfAPlaneIsItsDistanceWhereverThePixelSeesIt) {
  // A square 0.6 m wide, 2 m away, in the middle of a 0.5 rad field of view: the pixels along its
  // edges see it and the background. Depth is the nearest sample's, never a mix with the 1e10 m
  // of the background.
  constexpr float kDistance = 2.f, kHalfSide = 0.3f;
  const Scene scene =
      test::textured_quad({{-kHalfSide, -kHalfSide, -kDistance},
                           {kHalfSide, -kHalfSide, -kDistance},
                           {kHalfSide, kHalfSide, -kDistance},
                           {-kHalfSide, kHalfSide, -kDistance}},
                          false, 0.1f, 8, 2, 1.0, test::scratch_dir() / "passes_depth.gltf");
  RenderOptions options = test::texture_render_options(kPassImagePx, kPassImagePx, 16, false, 1);
  options.passes = {"Depth"};
  const Image image = RenderJob(scene, options, test::loader()).run().image;
  const size_t depth = channel_index(image, "ViewLayer.Depth.Z");
  const float half_extent_m = kDistance * std::tan(0.25f);
  const auto on_square = [&](float px, float py) {
    const float x = (2.f * px / kPassImagePx - 1.f) * half_extent_m;
    const float y = (1.f - 2.f * py / kPassImagePx) * half_extent_m;
    return std::abs(x) < kHalfSide && std::abs(y) < kHalfSide;
  };
  int inside = 0, outside = 0, edge_on_plane = 0;
  for (uint32_t y = 0; y < kPassImagePx; ++y)
    for (uint32_t x = 0; x < kPassImagePx; ++x) {
      int corners = 0;
      for (const float cx : {0.f, 1.f})
        for (const float cy : {0.f, 1.f})
          corners += on_square(float(x) + cx, float(y) + cy);
      const float z = image.at(x, y, depth);
      if (corners == 4) {
        ++inside;
        EXPECT_NEAR(z, kDistance, kDistance * 1e-6f) << x << "," << y;
      } else if (corners == 0) {
        ++outside;
        EXPECT_EQ(z, kMissDepthM) << x << "," << y;
      } else {
        // Some of its 16 samples see the plane (then it is the depth), or none did.
        if (z != kMissDepthM) {
          ++edge_on_plane;
          EXPECT_NEAR(z, kDistance, kDistance * 1e-6f) << x << "," << y;
        }
      }
    }
  EXPECT_GT(inside, 100);
  EXPECT_GT(outside, 100);
  EXPECT_GT(edge_on_plane, 20);
}

TEST(RenderPasses, NormalsOfASphereAreTheAnalyticNormalsAtThePixelCentres) {
  // A box filter 0.002 px wide keeps every sample at its pixel's centre. The sphere emits, so the
  // Emit pass is known too; the world is in the background.
  const Scene scene = ball_scene({2.f, 1.f, 0.5f});
  RenderOptions options = ball_options(4, "box:radius=0.001");
  options.passes = {"Normal", "Emit", "Denoising Normal"};
  const Image image = RenderJob(scene, options, test::loader()).run().image;
  const size_t normal = channel_index(image, "ViewLayer.Normal.X");
  const size_t denoising = channel_index(image, "ViewLayer.Denoising Normal.X");
  const size_t emit = channel_index(image, "ViewLayer.Emit.R");
  int on_ball = 0, off_ball = 0;
  for (uint32_t y = 0; y < kPassImagePx; ++y)
    for (uint32_t x = 0; x < kPassImagePx; ++x) {
      const double off_centre = ball_off_centre(x, y);
      if (off_centre > 1.05) {
        ++off_ball;
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(image.at(x, y, normal + c), 0.f) << x << "," << y;
          EXPECT_EQ(image.at(x, y, emit + c), 0.f) << x << "," << y;
        }
      }
      if (off_centre > 0.9) continue;  // near the limb a sample's offset tilts it
      const Vec3d d = ball_ray(x + 0.5, y + 0.5);
      ++on_ball;
      // The nearer root of |t d - c|^2 = r^2.
      const double b = dot(d, kPassBallCentre);
      const double t = b - std::sqrt(b * b - dot(kPassBallCentre, kPassBallCentre) +
                                     kPassBallRadius * kPassBallRadius);
      const Vec3d n = (t * d - kPassBallCentre) / kPassBallRadius;
      // Denoising Normal is in Cycles' camera space, +Z forward: here the world's, z flipped.
      const Vec3d n_camera{n.x, n.y, -n.z};
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(image.at(x, y, normal + c), n[c], 2e-3) << x << "," << y << " axis " << c;
        EXPECT_NEAR(image.at(x, y, denoising + c), n_camera[c], 2e-3) << x << "," << y;
      }
      EXPECT_FLOAT_EQ(image.at(x, y, emit + 0), 2.f);
      EXPECT_FLOAT_EQ(image.at(x, y, emit + 2), 0.5f);
    }
  EXPECT_GT(on_ball, 50);
  EXPECT_GT(off_ball, 500);
}

TEST(RenderPasses, DiffColOfATexturedWallIsItsTexel) {
  // The wall is a dielectric (metallic 0) without transmission: all of it is diffuse.
  const Scene scene = test::albedo_checker_wall(test::scratch_dir() / "passes_albedo.gltf");
  RenderOptions options = test::albedo_checker_options();
  options.passes = {"DiffCol", "Denoising Albedo"};
  const Image image = RenderJob(scene, options, test::loader()).run().image;
  for (const char* first : {"ViewLayer.DiffCol.R", "ViewLayer.Denoising Albedo.R"}) {
    const std::array<int, 2> pixels_checked = test::expect_checker_albedo(image, first);
    EXPECT_GT(pixels_checked[0], 100) << first;
    EXPECT_GT(pixels_checked[1], 100) << first;
  }
}

TEST(RenderPasses, DiffColAndGlossColOfABallAreItsLobesWeights) {
  // glTF's model (docs/blender.md, "Passes"): the diffuse base takes (1 - metallic) x
  // (1 - transmission) of the base colour; the specular layer over it all is white (its Fresnel
  // is in its evaluation), the dielectric's reflecting only while KHR_materials_specular is not 0.
  for (const float specular : {1.f, 0.f}) {
    Scene scene = ball_scene({});
    Material& m = scene.materials[0];
    m.metallic = 0.25f, m.transmission = 0.4f, m.specular = specular;
    RenderOptions options = ball_options(4, "box:radius=0.001");
    options.passes = {"DiffCol", "GlossCol"};
    const Image image = RenderJob(scene, options, test::loader()).run().image;
    const size_t diffuse = channel_index(image, "ViewLayer.DiffCol.R");
    const size_t glossy = channel_index(image, "ViewLayer.GlossCol.R");
    const Rgb expected_diffuse = m.base_color * (0.75f * 0.6f);
    const float expected_glossy = specular > 0.f ? 1.f : 0.25f;
    int on_ball = 0, off_ball = 0;
    for (uint32_t y = 0; y < kPassImagePx; ++y)
      for (uint32_t x = 0; x < kPassImagePx; ++x) {
        const double off_centre = ball_off_centre(x, y);
        const bool off = off_centre > 1.05;
        if (!off && off_centre > 0.95) continue;  // the limb: a mix
        off ? ++off_ball : ++on_ball;
        for (int c = 0; c < 3; ++c) {
          EXPECT_FLOAT_EQ(image.at(x, y, diffuse + c), off ? 0.f : expected_diffuse[c])
              << x << "," << y << " specular " << specular;
          EXPECT_FLOAT_EQ(image.at(x, y, glossy + c), off ? 0.f : expected_glossy)
              << x << "," << y << " specular " << specular;
        }
      }
    EXPECT_GT(on_ball, 50);
    EXPECT_GT(off_ball, 500);
  }
}

TEST(RenderPasses, CombinedIsBitIdenticalToTheBeautyWithoutPasses) {
  // A diffuse ball lit by the world: paths bounce, so the passes' work sits among the path's.
  const Scene scene = ball_scene({});
  RenderOptions options = ball_options(8, "gaussian");
  const Image beauty = RenderJob(scene, options, test::loader()).run().image;
  ASSERT_EQ(beauty.channels, (std::vector<std::string>{"R", "G", "B"}));
  options.passes.assign(
      {"Depth", "Normal", "DiffCol", "GlossCol", "Emit", "Denoising Albedo", "Denoising Normal"});
  const Image layers = RenderJob(scene, options, test::loader()).run().image;
  const size_t combined = channel_index(layers, "ViewLayer.Combined.R");
  const size_t alpha = channel_index(layers, "ViewLayer.Combined.A");
  ASSERT_EQ(channel_index(layers, "ViewLayer.Combined.G"), combined + 1);
  ASSERT_EQ(channel_index(layers, "ViewLayer.Combined.B"), combined + 2);
  size_t differing = 0;
  float brightest = 0.f;
  for (uint32_t y = 0; y < kPassImagePx; ++y)
    for (uint32_t x = 0; x < kPassImagePx; ++x) {
      for (size_t c = 0; c < 3; ++c) {
        differing += beauty.at(x, y, c) != layers.at(x, y, combined + c);
        brightest = std::max(brightest, beauty.at(x, y, c));
      }
      EXPECT_EQ(layers.at(x, y, alpha), 1.f);
    }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(brightest, 0.1f);  // not two black images
}

}  // namespace
}  // namespace fb
