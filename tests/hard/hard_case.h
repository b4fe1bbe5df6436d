// What every hard case (scenes/hard/README.md) shares: its scene file, a render through RenderJob
// with its time, and the line each case prints and checks: non-finite samples (must be 0), its
// error against its expectation (must be within the stated limit), and its time.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <filmback/vec.h>

#include "core/image/image.h"
#include "core/render/render_job.h"
#include "core/scene/scene.h"

namespace fb::test {

// scenes/hard/<name>, imported; the importer must have nothing to warn about.
Scene load_hard_scene(const std::string& name);

struct TimedRender {
  RenderResult result;
  double seconds = 0;
};
TimedRender render_timed(const Scene& scene, RenderOptions options);

// Options for comparing pixels with an analytic radiance averaged over their footprint: a box
// filter (each pixel the plain mean of its samples), `samples_per_pixel`, `integrator`.
RenderOptions box_filtered(uint32_t samples_per_pixel, const std::string& integrator);

// Prints `[ hard ] CASE: non-finite N, error E (limit L, what), T s`, records the three numbers as
// test properties, and fails the test unless N == 0 and E <= L.
void report_case(const std::string& name, uint64_t non_finite, double error, double limit,
                 const std::string& what, double seconds);

// Seconds since construction.
class Stopwatch {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// The pinhole ray through raster point (x, y) of the scene's first camera at width x height px,
// in world space: origin and unit direction (docs/camera-model.md, "The view plane").
struct WorldRay {
  Vec3d origin, direction;
};
WorldRay pixel_ray(const SceneCamera& camera, uint32_t width, uint32_t height, double x, double y);

// How far the pixels that see a diffuse plane are from its analytic radiance. Each pixel is traced
// at n x n points of its footprint (box filter) through the scene's first camera; where
// `on_plane(ray)` gives the point each ray meets the plane (nothing: the pixel is left out), its
// channel c is compared with `scale` times the mean of `radiance(point)` over them. The worst
// |pixel / expected - 1| and the mean of pixel / expected - 1 (signed: a bias).
struct PixelError {
  double worst = 0, mean = 0;
};
PixelError footprint_error(const Scene& scene, const Image& image, size_t c, int n, double scale,
                           const std::function<std::optional<Vec3d>(const WorldRay&)>& on_plane,
                           const std::function<double(Vec3d)>& radiance);

// Where a world point projects on that camera's raster (the pinhole formula).
Vec2d project(const SceneCamera& camera, uint32_t width, uint32_t height, Vec3d world);

// The instance whose glTF node has this name; throws if there is none.
const MeshInstance& instance_named(const Scene& scene, const std::string& node);

}  // namespace fb::test
