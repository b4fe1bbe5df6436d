#include "core/scene/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <filmback/camera_projection.h>

namespace fb {

fb_camera_setup make_camera_setup(const PhysicalCamera& camera, uint32_t width_px,
                                  uint32_t height_px, double pixel_aspect,
                                  const SensorResponse& sensor) {
  fb_camera_setup setup{};
  setup.struct_size = sizeof(fb_camera_setup);
  setup.projection = camera.projection;
  setup.image_width_px = width_px;
  setup.image_height_px = height_px;
  setup.pixel_aspect = pixel_aspect;
  setup.focal_length_mm = camera.focal_length_mm;
  setup.sensor_width_mm = camera.sensor_width_mm;
  setup.sensor_height_mm = camera.sensor_height_mm;
  setup.sensor_fit = camera.sensor_fit;
  setup.shift_x = camera.shift_x;
  setup.shift_y = camera.shift_y;
  setup.ortho_scale_m = camera.ortho_scale_m;
  setup.clip_near_m = camera.clip_near_m;
  setup.clip_far_m = camera.clip_far_m;
  setup.fstop = camera.fstop;
  setup.focus_distance_m = camera.focus_distance_m;
  setup.aperture_blades = camera.aperture_blades;
  setup.aperture_rotation_rad = camera.aperture_rotation_rad;
  setup.aperture_ratio = camera.aperture_ratio;
  setup.sensor_model = sensor.model;
  setup.exposure_time_s = sensor.exposure_time_s;
  setup.iso = sensor.iso;
  return setup;
}

CameraQuantities describe_camera(const PhysicalCamera& camera, uint32_t width_px,
                                 uint32_t height_px) {
  const ViewPlane v = view_plane(make_camera_setup(camera, width_px, height_px));
  constexpr double kDegrees = 180.0 / std::numbers::pi;
  constexpr double kFullFrameWidthMm = 36.0;
  const double kFullFrameDiagonalMm = std::hypot(36.0, 24.0);  // 43.27 mm
  CameraQuantities q{};
  q.horizontal_fit = v.horizontal_fit;
  if (camera.projection == FB_PROJECTION_ORTHOGRAPHIC) return q;  // no angles, no focal length
  // alpha = 2 atan(h / 2f) for an image side h on the sensor (docs/camera-model.md)
  q.horizontal_fov_deg = 2.0 * std::atan(v.extent_x / 2.0) * kDegrees;
  q.vertical_fov_deg = 2.0 * std::atan(v.extent_y / 2.0) * kDegrees;
  q.imaged_sensor_width_mm = v.extent_x * camera.focal_length_mm;
  q.imaged_sensor_height_mm = v.extent_y * camera.focal_length_mm;
  q.equivalent_35mm_width_mm =
      camera.focal_length_mm * kFullFrameWidthMm / q.imaged_sensor_width_mm;
  q.equivalent_35mm_diagonal_mm = camera.focal_length_mm * kFullFrameDiagonalMm /
                                  std::hypot(q.imaged_sensor_width_mm, q.imaged_sensor_height_mm);
  return q;
}

double FocusTrack::at(double frame) const {
  const double x = std::clamp(frame - first_frame, 0.0, double(distances_m.size() - 1));
  const size_t i = std::min(size_t(x), distances_m.size() - 1);
  if (i + 1 == distances_m.size()) return distances_m[i];
  return std::lerp(distances_m[i], distances_m[i + 1], x - double(i));
}

}  // namespace fb
