// Whole renders of glTF metallic-roughness surfaces in a uniform world (a furnace): a plane seen
// at cos(theta) = mu in a world of radiance L returns L times the BSDF's directional albedo at mu,
// which quadrature of filmback/bsdf.h gives independently of the integrator, the host's hit records
// and the shading frame that this test exercises.
#include "core/shading/gltf_bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/render/render_job.h"
#include "core/texture/surface_shader.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"
#include "support/png.h"

namespace fb {
namespace {

using test::GltfBuilder;

// Directional albedo: integral over the sphere of f(wo, wi) |cos wi|, midpoint rule in (theta,
// phi), whose rows stay narrow at the poles where a lobe seen at normal incidence peaks.
double albedo(const BsdfParams& params, double mu, int n = 1000) {
  const Bsdf bsdf(params);
  const double s = std::sqrt(1 - mu * mu);
  const Vec3f wo(Vec3d{s, 0, mu});
  const double d_theta = std::numbers::pi / (2 * n), d_phi = 2 * std::numbers::pi / n;
  double sum = 0;
  for (int i = 0; i < 2 * n; ++i) {
    const double theta = (i + 0.5) * d_theta;
    const double c = std::cos(theta), r = std::sin(theta);
    for (int j = 0; j < n; ++j) {
      const double phi = (j + 0.5) * d_phi;
      const Vec3f wi(Vec3d{r * std::cos(phi), r * std::sin(phi), c});
      sum += bsdf.eval(wo, wi).y * std::abs(c) * r;
    }
  }
  return sum * d_theta * d_phi;
}

struct Furnace {
  const char* name;
  float metallic, roughness, transmission;
};

// The world is the uniform background (found by BSDF sampling only), an emissive box around the
// scene (found by both light and BSDF sampling, weighted by the power heuristic: the weights must
// sum to one for the answer to hold), or that box with a grey emissive texture (light sampling
// must evaluate the texture where it samples, or the two strategies disagree).
enum class World { kBackground, kEmissiveBox, kTexturedEmissiveBox };

Scene furnace_scene(double tilt_deg, World world, float radiance) {
  GltfBuilder gltf;
  const float h = world == World::kBackground ? 50.f : 2.f;
  const std::vector<Vec3f> quad = {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}};
  GltfBuilder::Node plane;
  plane.mesh = gltf.mesh(quad, {0, 1, 2, 0, 2, 3}, gltf.material({1, 1, 1}), 5125,
                         std::vector<Vec3f>(4, Vec3f{0, 0, 1}));
  const double half = tilt_deg * std::numbers::pi / 360;
  plane.translation = {0, 0, -5};
  plane.rotation = {std::sin(half), 0, 0, std::cos(half)};
  gltf.node(plane);
  if (world != World::kBackground) {
    constexpr float b = 20.f;  // a cube of side 2b about the camera, emitting inwards and out
    std::vector<Vec3f> corners;
    for (int i = 0; i < 8; ++i)
      corners.push_back({i & 1 ? b : -b, i & 2 ? b : -b, i & 4 ? b : -b});
    const std::vector<uint32_t> faces = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                         2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
    GltfBuilder::Node box;
    box.mesh = gltf.mesh(corners, faces, gltf.material({0, 0, 0}, {1, 1, 1}, radiance));
    gltf.node(box);
  }
  GltfBuilder::Node camera;
  camera.camera = gltf.orthographic_camera(0.5, 0.5, 0.1, 100);
  gltf.node(camera);
  Diagnostics diagnostics;
  Scene scene = import_gltf(gltf.write(test::scratch_dir() / "furnace.gltf"), diagnostics);
  if (world == World::kBackground) scene.background = {radiance, radiance, radiance};
  if (world == World::kTexturedEmissiveBox) {
    // A grey emissive texture (sRGB 128: 0.2158 of the factor): light sampling must see it too.
    scene.images.push_back({"images[0]", {}, test::png(1, 1, {128, 128, 128, 255})});
    scene.materials.back().textures.emissive.image = 0;
  }
  return scene;
}

TEST(MaterialRender, PlaneInAUniformWorldReturnsItsDirectionalAlbedo) {
  constexpr float kL = 2.f;  // the world's radiance
  for (World world : {World::kBackground, World::kEmissiveBox, World::kTexturedEmissiveBox})
    for (double tilt_deg : {0.0, 60.0}) {
      const Scene base = furnace_scene(tilt_deg, world, kL);
      const double mu = std::cos(tilt_deg * std::numbers::pi / 180);
      for (const Furnace& f :
           {Furnace{"rough metal", 1.f, 0.5f, 0.f}, Furnace{"glossy dielectric", 0.f, 0.3f, 0.f},
            Furnace{"rough glass", 0.f, 0.4f, 1.f}}) {
        Scene scene = base;
        Material& m = scene.materials[0];  // the plane's
        m.metallic = f.metallic, m.roughness = f.roughness, m.transmission = f.transmission;
        m.specular = 1.f;
        RenderOptions options;
        options.width = options.height = 16;
        options.samples_per_pixel = 64;
        options.filter = "box";
        options.show_progress = false;
        const RenderResult result = RenderJob(scene, options, test::loader()).run();
        // Pixels are independent estimates: their spread gives the standard error of the mean.
        double sum = 0, sum2 = 0;
        const int n = 16 * 16;
        for (uint32_t y = 0; y < 16; ++y)
          for (uint32_t x = 0; x < 16; ++x) {
            const double v = result.image.at(x, y, 1);
            ASSERT_TRUE(std::isfinite(v));
            sum += v, sum2 += v * v;
          }
        const double mean = sum / n;
        const double standard_error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
        const double world_radiance =
            kL * (world == World::kTexturedEmissiveBox ? srgb_to_linear(128 / 255.f) : 1.f);
        const double expected =
            world_radiance *
            albedo({{1, 1, 1}, f.metallic, f.roughness, f.transmission, 1.5f, 1.f}, mu);
        EXPECT_NEAR(mean, expected, 4 * standard_error + 2e-3 * expected)
            << f.name << " at mu " << mu << " in world " << int(world) << ", standard error "
            << standard_error;
      }
    }
}

}  // namespace
}  // namespace fb
