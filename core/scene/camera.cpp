#include "core/scene/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <filmback/camera_projection.h>

namespace fb {

std::optional<double> fstop_from(double n) {
  if (n == 0 || n == HUGE_VAL) return HUGE_VAL;
  if (n > 0 && n <= kMaxFstop) return n;
  return std::nullopt;
}

namespace {

// Each value's name and member, in CameraValue order.
struct CameraMember {
  const char* name;
  double PhysicalCamera::*number;
  uint32_t PhysicalCamera::*whole;
};
constexpr CameraMember kMembers[kCameraValueCount] = {
    {"focal_length_mm", &PhysicalCamera::focal_length_mm, nullptr},
    {"sensor_width_mm", &PhysicalCamera::sensor_width_mm, nullptr},
    {"sensor_height_mm", &PhysicalCamera::sensor_height_mm, nullptr},
    {"sensor_fit", nullptr, &PhysicalCamera::sensor_fit},
    {"shift_x", &PhysicalCamera::shift_x, nullptr},
    {"shift_y", &PhysicalCamera::shift_y, nullptr},
    {"ortho_scale_m", &PhysicalCamera::ortho_scale_m, nullptr},
    {"clip_near_m", &PhysicalCamera::clip_near_m, nullptr},
    {"clip_far_m", &PhysicalCamera::clip_far_m, nullptr},
    {"fstop", &PhysicalCamera::fstop, nullptr},
    {"focus_distance_m", &PhysicalCamera::focus_distance_m, nullptr},
    {"aperture_blades", nullptr, &PhysicalCamera::aperture_blades},
    {"aperture_rotation_rad", &PhysicalCamera::aperture_rotation_rad, nullptr},
    {"aperture_ratio", &PhysicalCamera::aperture_ratio, nullptr},
};

}  // namespace

const char* camera_value_name(CameraValue v) {
  return kMembers[size_t(v)].name;
}

double camera_value(const PhysicalCamera& camera, CameraValue v) {
  const CameraMember& m = kMembers[size_t(v)];
  return m.number ? camera.*m.number : double(camera.*m.whole);
}

void set_camera_value(PhysicalCamera& camera, CameraValue v, double x) {
  const CameraMember& m = kMembers[size_t(v)];
  if (m.number)
    camera.*m.number = x;
  else
    camera.*m.whole = uint32_t(x);
}

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

double LensTrack::at(CameraValue v, double frame) const {
  const std::vector<double>& track = values[size_t(v)];
  const double x = std::clamp(frame - first_frame, 0.0, double(track.size() - 1));
  const size_t i = std::min(size_t(x), track.size() - 1);
  if (i + 1 == track.size()) return track[i];
  return std::lerp(track[i], track[i + 1], x - double(i));
}

void LensTrack::apply(double frame, PhysicalCamera& camera) const {
  for (CameraValue v : kTracked)
    if (tracks(v)) set_camera_value(camera, v, at(v, frame));
}

}  // namespace fb
