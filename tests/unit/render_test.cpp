// Whole renders through RenderJob on scenes written as glTF, checked against closed forms.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

#include "core/render/render_job.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

std::vector<Vec3f> square(float half, float z) {
  return {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
}
const std::vector<uint32_t> kSquare = {0, 1, 2, 0, 2, 3};

RenderResult render(const Scene& scene, RenderOptions options) {
  options.show_progress = false;
  const RenderJob job(scene, options, test::loader());
  return job.run();
}

TEST(Render, EmissiveQuadFillingTheViewReturnsItsEmissionInEveryPixel) {
  GltfBuilder gltf;
  const Rgb emission{0.25f, 1.5f, 3.f};
  GltfBuilder::Node wall;
  wall.mesh = gltf.mesh(square(100, -5), kSquare, gltf.material({0, 0, 0}, emission / 4.f, 4.0));
  gltf.node(wall);
  GltfBuilder::Node camera;
  camera.camera = gltf.perspective_camera(1.0, 1.5, 0.1, 100);
  gltf.node(camera);
  const Scene scene = test::import_built(gltf, "wall.gltf");
  for (const char* filter : {"box", "gaussian"}) {
    RenderOptions options;
    options.width = 48, options.height = 32, options.samples_per_pixel = 3;
    options.filter = filter;
    const RenderResult result = render(scene, options);
    EXPECT_EQ(result.stats.dropped_samples, 0u);
    for (uint32_t y = 0; y < 32; ++y)
      for (uint32_t x = 0; x < 48; ++x)
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(result.image.at(x, y, c), emission[c], 1e-6 * emission[c])
              << filter << " at " << x << "," << y;
  }
}

// A point light of intensity I at height h over a Lambertian floor of albedo rho: the floor's
// radiance is L = rho / pi * I cos(theta) / d^2 (direct light only: max_depth=1).
TEST(Render, PointLightOverLambertianFloorMatchesTheInverseSquareLaw) {
  GltfBuilder gltf;
  const float rho = 0.6f, height = 2.f;
  const double intensity_w_sr = 5.0;
  GltfBuilder::Node floor;
  floor.mesh = gltf.mesh({{-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}}, kSquare,
                         gltf.material({rho, rho, rho}));
  gltf.node(floor);
  GltfBuilder::Node light;
  light.light = gltf.point_light({1, 1, 1}, intensity_w_sr * kLumensPerWatt);
  light.translation = {0, height, 0};
  gltf.node(light);
  GltfBuilder::Node camera;  // straight down from above the light, narrow view
  camera.camera = gltf.perspective_camera(0.5, 1.0, 0.01, 100);
  camera.translation = {0, 3, 0};
  camera.rotation = {-std::sin(std::numbers::pi / 4), 0, 0, std::cos(std::numbers::pi / 4)};
  gltf.node(camera);
  const Scene scene = test::import_built(gltf, "floor.gltf");
  RenderOptions options;
  options.width = options.height = 33;
  options.samples_per_pixel = 256;  // the pixel-average's sampling error: ~0.05 % here
  options.filter = "box";
  options.integrator = "path:max_depth=1";
  const Image image = render(scene, options).image;
  // The floor point seen at raster (px, py): on this axis-aligned downward camera the ray through
  // the pixel centre meets y = 0 at camera-plane offsets scaled by the height 3 m.
  const double f = (33 / 2.0) / std::tan(0.25);
  for (auto [px, py] : {std::pair{16, 16}, {4, 16}, {30, 3}}) {
    // Average the analytic radiance over the pixel footprint (the box filter's support).
    double expected = 0;
    const int n = 20;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double sx = px + (i + 0.5) / n, sy = py + (j + 0.5) / n;
        const double x = 3 * (sx - 16.5) / f, z = 3 * (sy - 16.5) / f;  // image down = world +z
        const double d2 = x * x + z * z + height * height;
        expected += rho / std::numbers::pi * intensity_w_sr * (height / std::sqrt(d2)) / d2;
      }
    expected /= n * n;
    EXPECT_NEAR(image.at(px, py, 1), expected, 2e-3 * expected) << px << "," << py;
  }
}

// A closed box of Lambertian walls of albedo a, each emitting L_e, seen from inside: the radiance
// is uniform, L = L_e (1 + a + ... + a^M) after at most M bounces (the rendering equation's
// Neumann series with a constant field). Russian roulette ends paths from the first bounce on
// (path's default, Cycles' rule), so this checks that it leaves the mean unbiased, against
// the noise of the image mean (the pixels' spread over sqrt(pixels)).
TEST(Render, RussianRouletteKeepsAnInterreflectingBoxAtTheNeumannSeries) {
  GltfBuilder gltf;
  const float albedo = 0.5f, emission = 2.f;
  const int material = gltf.material({albedo, albedo, albedo}, {emission, emission, emission});
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.f, 1.f}) {
      std::vector<Vec3f> face;
      for (const Vec3f& q : square(1, side))  // the square at z = side, turned onto `axis`
        face.push_back(axis == 2 ? q : axis == 0 ? Vec3f{q.z, q.x, q.y} : Vec3f{q.y, q.z, q.x});
      GltfBuilder::Node wall;
      wall.mesh = gltf.mesh(face, kSquare, material);
      gltf.node(wall);
    }
  GltfBuilder::Node camera;
  camera.camera = gltf.perspective_camera(1.2, 1.0, 0.01, 10);
  gltf.node(camera);
  const Scene scene = test::import_built(gltf, "closed_box.gltf");
  const int max_depth = 6;
  RenderOptions options;
  options.width = options.height = 16;
  options.samples_per_pixel = 64;
  options.integrator = "path:max_depth=" + std::to_string(max_depth);
  const RenderResult result = render(scene, options);
  double sum = 0, squares = 0;
  const double n = 16.0 * 16.0;
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const double v = result.image.at(x, y, 1);
      sum += v, squares += v * v;
    }
  const double mean = sum / n, error_of_mean = std::sqrt((squares / n - mean * mean) / (n - 1));
  const double expected = emission * (1 - std::pow(albedo, max_depth + 1)) / (1 - albedo);
  EXPECT_LT(error_of_mean, 0.01 * expected);  // the test can tell a 5 % bias
  EXPECT_NEAR(mean, expected, 4 * error_of_mean) << "error of the mean " << error_of_mean;
}

TEST(Render, ImageIsBitIdenticalForAnyThreadCount) {
  GltfBuilder gltf;
  GltfBuilder::Node floor, lamp, light;
  floor.mesh = gltf.mesh(square(3, 0), kSquare, gltf.material({0.7f, 0.6f, 0.5f}));
  floor.rotation = {-std::sin(std::numbers::pi / 4), 0, 0, std::cos(std::numbers::pi / 4)};
  lamp.mesh = gltf.mesh(square(0.5f, 0), kSquare, gltf.material({0, 0, 0}, {4, 4, 4}));
  lamp.translation = {0, 2, 0};
  lamp.rotation = {std::sin(std::numbers::pi / 4), 0, 0, std::cos(std::numbers::pi / 4)};
  light.light = gltf.point_light({1, 0.8f, 0.6f}, 683.0);
  light.translation = {1, 1, 1};
  gltf.node(floor), gltf.node(lamp), gltf.node(light);
  const Scene scene =
      test::import_built(gltf, "threads.gltf");  // no camera: the default one frames it
  RenderOptions options;
  options.width = 40, options.height = 24, options.samples_per_pixel = 4, options.seed = 9;
  std::vector<float> pixels[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    pixels[threads - 1] = render(scene, options).image.pixels;
  }
  EXPECT_EQ(pixels[0], pixels[1]);
  double sum = 0;
  for (float v : pixels[0])
    sum += v;
  EXPECT_GT(sum, 0.0) << "the default camera should see the lit floor";
}

}  // namespace
}  // namespace fb
