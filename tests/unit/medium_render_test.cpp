// The `path` integrator in a scene's medium (POV-Ray's fog as the absorbing, emitting medium it
// maps to, docs/pov.md "Fog") against the closed form of radiative transfer: an emitter seen
// through the fog, the fog alone where rays escape, and light reaching a surface through it.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/render_job.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

constexpr uint32_t kFogShotSize = 32;
constexpr double kFogShotFov = 0.7;   // rad, vertical; square frame
constexpr double kFogWallDepth = 4;   // m in front of the camera
constexpr double kFogDistance_m = 3;  // the fog's distance: e^-1 left after 3 m
// Float rays and the film's float sums: far below the differences the fog makes.
constexpr float kFogRenderTolerance = 2e-5f;

// A camera at the origin looking down -Z at a 2 m square at kFogWallDepth of material `material`,
// which leaves the frame's corners open to the world, optionally lit by a point light at `light`.
Scene wall_scene(Rgb base_color, Rgb emission, const Vec3f* light = nullptr) {
  GltfBuilder gltf;
  const float z = -float(kFogWallDepth);
  GltfBuilder::Node wall;
  wall.mesh = gltf.mesh({{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}}, {0, 1, 2, 0, 2, 3},
                        gltf.material(base_color, emission));
  gltf.node(wall);
  GltfBuilder::Node camera;
  camera.camera = gltf.perspective_camera(kFogShotFov, 1.0, 0.01, 1000);
  gltf.node(camera);
  if (light) {
    GltfBuilder::Node lamp;
    lamp.light = gltf.point_light({1, 1, 1}, 10);
    lamp.translation = {light->x, light->y, light->z};
    gltf.node(lamp);
  }
  Scene scene = test::import_built(gltf, "fog_wall.gltf");
  scene.background = {5.f, 5.f, 5.f};  // hidden by constant fog wherever it is seen
  return scene;
}

GlobalMedium wall_fog(Rgb colour) {
  GlobalMedium fog;
  fog.colour = colour;
  fog.distance_m = kFogDistance_m;
  return fog;
}

Image render_through_pixel_centres(const Scene& scene, const char* integrator) {
  RenderOptions options;
  options.width = options.height = kFogShotSize;
  options.samples_per_pixel = 1;
  options.filter = "box:radius=0.001";
  options.integrator = integrator;
  options.show_progress = false;
  return RenderJob(scene, options, test::loader()).run().image;
}

// The distance from the camera to the wall through the centre of pixel (i, j).
double wall_distance(uint32_t i, uint32_t j) {
  const double per_pixel = 2 * std::tan(kFogShotFov / 2) / kFogShotSize;
  const double x = (i + 0.5 - kFogShotSize / 2.0) * per_pixel;
  const double y = (j + 0.5 - kFogShotSize / 2.0) * per_pixel;
  return kFogWallDepth * std::sqrt(1 + x * x + y * y);
}

// L = e^-tau L_emitter + (1 - e^-tau) colour, tau = distance / fog distance; a ray that escapes
// sees the fog's colour, whatever the world behind it.
TEST(PathInFog, EmitterThroughConstantFogIsTheClosedForm) {
  const Rgb emission{1.f, 0.5f, 0.25f}, fog_colour{0.2f, 0.4f, 0.6f};
  Scene scene = wall_scene({0.f, 0.f, 0.f}, emission);
  scene.media.push_back(wall_fog(fog_colour));
  const Image image = render_through_pixel_centres(scene, "path:max_depth=0");
  for (uint32_t j : {15u, 16u, 20u})
    for (uint32_t i : {15u, 16u, 9u}) {
      const float through = float(std::exp(-wall_distance(i, j) / kFogDistance_m));
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(image.at(i, j, c), emission[c] * through + fog_colour[c] * (1 - through),
                    kFogRenderTolerance)
            << i << "," << j << " channel " << c;
    }
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(image.at(0, 0, c), fog_colour[c], kFogRenderTolerance);
}

// Direct light on a diffuse wall is dimmed along the shadow ray and the camera ray alike: with a
// black fog the ratio to the clear render is e^-(light distance + camera distance) / distance.
TEST(PathInFog, LightReachesASurfaceThroughTheFog) {
  const Vec3f light{0, 0, -1};
  Scene clear = wall_scene({0.8f, 0.8f, 0.8f}, {}, &light);
  clear.background = {};  // the wall's only light is the lamp's
  Scene foggy = clear;
  foggy.media.push_back(wall_fog({}));
  const Image lit = render_through_pixel_centres(clear, "path:max_depth=1");
  const Image dimmed = render_through_pixel_centres(foggy, "path:max_depth=1");
  for (uint32_t i : {16u, 10u}) {
    const uint32_t j = 16;
    const double per_pixel = 2 * std::tan(kFogShotFov / 2) / kFogShotSize;
    const double x = kFogWallDepth * (i + 0.5 - kFogShotSize / 2.0) * per_pixel;
    const double y = kFogWallDepth * (j + 0.5 - kFogShotSize / 2.0) * per_pixel;
    const double to_light = std::sqrt(x * x + y * y + 9);  // the light is 3 m from the wall
    const double expected = std::exp(-(wall_distance(i, j) + to_light) / kFogDistance_m);
    ASSERT_GT(lit.at(i, j, 1), 0.f);
    EXPECT_NEAR(dimmed.at(i, j, 1) / lit.at(i, j, 1), expected, 1e-4) << i;
  }
}

}  // namespace
}  // namespace fb
