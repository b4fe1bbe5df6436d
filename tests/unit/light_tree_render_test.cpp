// Whole renders of a floor under many small lamps with the light tree and with power sampling
// (core/render/light_choice.h): both estimate the same image, the closed form's.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/render/render_job.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

constexpr float kAlbedo = 0.5f, kFloorZ = -5.f, kHalfView = 2.f;

// A Lambertian floor (z = -5, facing the camera at the origin, which looks down -z through an
// orthographic view of 4 x 4 m) under 64 lamps 1 to 3 m above it, of 0.01 to 100 W/sr, every
// other one a sphere of 1 to 3 cm (Cycles 3.4's soft point light).
Scene floor_under_lamps() {
  GltfBuilder gltf;
  GltfBuilder::Node floor;
  const float b = 50.f;
  floor.mesh = gltf.mesh({{-b, -b, kFloorZ}, {b, -b, kFloorZ}, {b, b, kFloorZ}, {-b, b, kFloorZ}},
                         {0, 1, 2, 0, 2, 3}, gltf.material({kAlbedo, kAlbedo, kAlbedo}));
  gltf.node(floor);
  std::mt19937 rng(64);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> radii;
  for (int i = 0; i < 64; ++i) {
    GltfBuilder::Node lamp;
    lamp.light = gltf.point_light({1, 1, 1}, std::pow(10.0, 4 * unit(rng) - 2) * kLumensPerWatt);
    lamp.translation = {8 * unit(rng) - 4, 8 * unit(rng) - 4, kFloorZ + 1 + 2 * unit(rng)};
    radii.push_back(i % 2 ? 0.01 + 0.02 * unit(rng) : 0.0);
    gltf.node(lamp);
  }
  GltfBuilder::Node camera;
  camera.camera = gltf.orthographic_camera(kHalfView, kHalfView, 0.1, 100);
  gltf.node(camera);
  Diagnostics diagnostics;
  Scene scene = import_gltf(gltf.write(test::scratch_dir() / "lamps.gltf"), diagnostics);
  for (size_t i = 0; i < scene.lights.size(); ++i)
    scene.lights[i].radius_m = radii[i];
  return scene;
}

// The floor's mean radiance over the view, rho / pi times its mean irradiance, each lamp's
// I cos / (d^2 + r^2) (exact for a disk facing the point on its axis; off the axis within
// r^2 / d^2 <= 1e-3 here), averaged by the midpoint rule on 400 x 400 points (the integrand is
// smooth: every lamp is 1 m or more away).
double closed_form_mean(const Scene& scene) {
  constexpr int kGrid = 400;
  double sum = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Vec3d p{kHalfView * (2 * (i + 0.5) / kGrid - 1),
                    kHalfView * (2 * (j + 0.5) / kGrid - 1), kFloorZ};
      for (const Light& light : scene.lights) {
        const Vec3d d = scene.world_from_light(light, 0).point({0, 0, 0}) - p;
        const double d2 = dot(d, d);
        sum += light.intensity.y * (d.z / std::sqrt(d2)) / (d2 + light.radius_m * light.radius_m);
      }
    }
  return kAlbedo / std::numbers::pi * sum / (kGrid * kGrid);
}

struct Estimate {
  double mean, standard_error;
};

// The image's mean over `seeds` renders, and its standard error from their spread.
Estimate image_mean(const Scene& scene, LightSelection selection, int seeds) {
  double sum = 0, sum2 = 0;
  for (int seed = 0; seed < seeds; ++seed) {
    RenderOptions options;
    options.width = options.height = 24;
    options.samples_per_pixel = 8;
    options.filter = "box";  // each sample in its pixel: the image averages the view
    options.integrator = "path:max_depth=1";
    options.light_selection = selection;
    options.seed = uint64_t(seed);
    options.show_progress = false;
    const RenderResult result = RenderJob(scene, options, test::loader()).run();
    double image = 0;
    for (uint32_t y = 0; y < 24; ++y)
      for (uint32_t x = 0; x < 24; ++x)
        image += result.image.at(x, y, 1);
    image /= 24 * 24;
    sum += image, sum2 += image * image;
  }
  const double mean = sum / seeds;
  return {mean, std::sqrt(std::max(0.0, sum2 / seeds - mean * mean) / (seeds - 1))};
}

// Both samplers' image means agree with each other and with the closed form within 4.5 standard
// errors (estimated from 8 seeds each: the noise floor is that spread, about 1 % of the mean with
// power sampling here); the tree's error is the smaller.
TEST(LightTreeRender, ManySmallLampsRenderTheSameFloorWithTheTreeAndByPower) {
  const Scene scene = floor_under_lamps();
  ASSERT_EQ(scene.lights.size(), 64u);
  EXPECT_NEAR(scene.world_from_light(scene.lights[0], 0).point({0, 0, 0}).z, kFloorZ, 3.01)
      << "the importer kept glTF's axes";
  const double expected = closed_form_mean(scene);
  constexpr int kSeeds = 8;
  const Estimate tree = image_mean(scene, LightSelection::kTree, kSeeds);
  const Estimate power = image_mean(scene, LightSelection::kPower, kSeeds);
  EXPECT_NEAR(tree.mean, expected, 4.5 * tree.standard_error + 1e-3 * expected);
  EXPECT_NEAR(power.mean, expected, 4.5 * power.standard_error + 1e-3 * expected);
  EXPECT_NEAR(tree.mean, power.mean,
              4.5 * std::hypot(tree.standard_error, power.standard_error) + 1e-3 * expected);
  EXPECT_LT(tree.standard_error, power.standard_error);
  std::cout << "closed form " << expected << ", tree " << tree.mean << " +- " << tree.standard_error
            << ", power " << power.mean << " +- " << power.standard_error << '\n';
}

}  // namespace
}  // namespace fb
