// What every hard case (scenes/hard/README.md) shares: its scene file, a render through RenderJob
// with its time, and the line each case prints and checks: non-finite samples (must be 0), its
// error against its expectation (must be within the stated limit), and its time.
#pragma once

#include <chrono>
#include <cstdint>
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

// Where a world point projects on that camera's raster (the pinhole formula).
Vec2d project(const SceneCamera& camera, uint32_t width, uint32_t height, Vec3d world);

// The instance whose glTF node has this name; throws if there is none.
const MeshInstance& instance_named(const Scene& scene, const std::string& node);

}  // namespace fb::test
