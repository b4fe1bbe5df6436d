#include "hard_case.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <filmback/camera_projection.h>

#include "core/util/diagnostics.h"
#include "importers/gltf/gltf_importer.h"
#include "support/plugins.h"

namespace fb::test {

Scene load_hard_scene(const std::string& name) {
  Diagnostics diagnostics;
  Scene scene = import_gltf(std::filesystem::path(FILMBACK_HARD_SCENES) / name, diagnostics);
  std::ostringstream warnings;
  diagnostics.print(warnings);
  EXPECT_EQ(warnings.str(), "") << name;
  return scene;
}

TimedRender render_timed(const Scene& scene, RenderOptions options) {
  options.show_progress = false;
  const Stopwatch clock;
  const RenderJob job(scene, options, loader());
  RenderResult result = job.run();
  return {std::move(result), clock.seconds()};
}

RenderOptions box_filtered(uint32_t samples_per_pixel, const std::string& integrator) {
  RenderOptions options;
  options.samples_per_pixel = samples_per_pixel;
  options.filter = "box";
  options.integrator = integrator;
  return options;
}

void report_case(const std::string& name, uint64_t non_finite, double error, double limit,
                 const std::string& what, double seconds) {
  std::printf("[   hard   ] %s: non-finite %llu, error %.4g (limit %.4g, %s), %.2f s\n",
              name.c_str(), static_cast<unsigned long long>(non_finite), error, limit, what.c_str(),
              seconds);
  std::fflush(stdout);
  ::testing::Test::RecordProperty(name + ".non_finite", std::to_string(non_finite));
  ::testing::Test::RecordProperty(name + ".error", std::to_string(error));
  ::testing::Test::RecordProperty(name + ".seconds", std::to_string(seconds));
  EXPECT_EQ(non_finite, 0u) << name;
  EXPECT_LE(error, limit) << name << ": " << what;
}

namespace {

ViewPlane plane_of(const SceneCamera& camera, uint32_t width, uint32_t height) {
  return view_plane(make_camera_setup(camera.physical, width, height));
}

}  // namespace

WorldRay pixel_ray(const SceneCamera& camera, uint32_t width, uint32_t height, double x, double y) {
  const ViewPlane v = plane_of(camera, width, height);
  const Vec3d d = normalize(Vec3d{(x - v.cx) / v.fx, -(y - v.cy) / v.fy, -1.0});
  return {camera.world_from_camera.point({0, 0, 0}), normalize(camera.world_from_camera.vector(d))};
}

PixelError footprint_error(const Scene& scene, const Image& image, size_t c, int n, double scale,
                           const std::function<std::optional<Vec3d>(const WorldRay&)>& on_plane,
                           const std::function<double(Vec3d)>& radiance) {
  PixelError e;
  size_t pixels = 0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      double expected = 0;
      bool inside = true;
      for (int j = 0; j < n && inside; ++j)
        for (int i = 0; i < n && inside; ++i) {
          const std::optional<Vec3d> p =
              on_plane(pixel_ray(scene.cameras.at(0), image.width, image.height, x + (i + 0.5) / n,
                                 y + (j + 0.5) / n));
          inside = p.has_value();
          if (inside) expected += radiance(*p);
        }
      if (!inside) continue;
      expected *= scale / (n * n);
      const double relative = image.at(x, y, c) / expected - 1;
      e.worst = std::max(e.worst, std::abs(relative));
      e.mean += relative;
      ++pixels;
    }
  e.mean /= double(pixels);
  return e;
}

Vec2d project(const SceneCamera& camera, uint32_t width, uint32_t height, Vec3d world) {
  const ViewPlane v = plane_of(camera, width, height);
  const Vec3d p = camera.world_from_camera.inverse().point(world);
  return {v.cx + v.fx * p.x / -p.z, v.cy - v.fy * p.y / -p.z};
}

const MeshInstance& instance_named(const Scene& scene, const std::string& node) {
  for (const MeshInstance& instance : scene.instances)
    if (instance.node == node) return instance;
  throw std::runtime_error(scene.file.string() + " has no mesh node '" + node + "'");
}

}  // namespace fb::test
