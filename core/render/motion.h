// Time for the render loop (docs/camera-model.md, "Time and motion"): how a camera ray's time is
// drawn from the shutter, and where a moving camera is at that time.
#pragma once

#include <optional>

#include <filmback/plugin_abi.h>

#include "core/math/transform.h"
#include "core/render/shutter.h"
#include "core/scene/scene.h"

namespace fb {

// Times relative to the frame's time, in seconds, as fb_camera_sample::time_s carries them.
struct TimeSampling {
  const ShutterCurve* curve = nullptr;  // null: no time samples, every ray at the frame's time
  double open_s = 0, close_s = 0;
  std::optional<RollingShutter> rolling;
  uint32_t height_px = 0;  // of the film, for the rolling shutter's rows
  // The fraction of the open shutter (0 at open, 1 at close) of a ray of film row `row` (0 at
  // the top) drawn with the sample u.
  double fraction(float u, double row) const {
    const double s = curve->sample(u);
    return rolling ? rolling->fraction(s, row, height_px) : s;
  }
  float time_s(double fraction) const { return float(open_s + (close_s - open_s) * fraction); }
};

// A camera that moves while the shutter is open. Render space stays centred on the camera at the
// frame's time; each ray leaves from where the camera is at the ray's own time, placed in double
// precision before it is narrowed to float.
class CameraPath {
 public:
  CameraPath(const Scene& scene, const SceneCamera& camera, const Transform& render_from_world,
             double frame_s)
      : scene_(scene), camera_(camera), render_from_world_(render_from_world), frame_s_(frame_s) {}
  // The camera-space ray `ray` in render space at `time_s` after the frame's time.
  void place(const fb_camera_ray& ray, float time_s, fb_ray& out) const;

 private:
  const Scene& scene_;
  SceneCamera camera_;
  Transform render_from_world_;
  double frame_s_;
};

}  // namespace fb
