// Blender's view plane (BKE_camera_params_compute_viewplane), the one place where the physical
// camera (focal length, sensor, fit, shift) becomes a projection. Cameras, `filmback info`, the
// EXR metadata and the tests all use it, so every path meets the same arithmetic.
// Derivation and measurements: docs/camera-model.md and shared notes/blender-camera.md.
#pragma once

#include <cmath>

#include "plugin_abi.h"

namespace fb {

struct ViewPlane {
  // raster = (cx + fx * X / -Z, cy - fy * Y / -Z) in perspective, (cx + fx X, cy - fy Y) in ortho
  double fx, fy, cx, cy;
  // full extent of the view plane at unit depth (perspective) or in metres (orthographic)
  double extent_x, extent_y;
  bool horizontal_fit;
};

inline bool fits_horizontally(const fb_camera_setup& c) {
  if (c.sensor_fit == FB_SENSOR_FIT_AUTO)
    return c.image_width_px * c.pixel_aspect >= c.image_height_px;
  return c.sensor_fit == FB_SENSOR_FIT_HORIZONTAL;
}

// The sensor dimension the fit applies to. AUTO uses the width even when the fit resolves to
// vertical (portrait), as Blender does: sensor_width then spans the image height.
inline double fitted_sensor_mm(const fb_camera_setup& c) {
  return c.sensor_fit == FB_SENSOR_FIT_VERTICAL ? c.sensor_height_mm : c.sensor_width_mm;
}

inline ViewPlane view_plane(const fb_camera_setup& c) {
  const double width = c.image_width_px, height = c.image_height_px;
  const double aspect = width * c.pixel_aspect / height;
  const double s = c.projection == FB_PROJECTION_ORTHOGRAPHIC
                       ? c.ortho_scale_m
                       : fitted_sensor_mm(c) / c.focal_length_mm;
  ViewPlane v{};
  v.horizontal_fit = fits_horizontally(c);
  v.extent_x = v.horizontal_fit ? s : s * aspect;
  v.extent_y = v.horizontal_fit ? s / aspect : s;
  v.fx = width / v.extent_x;
  v.fy = height / v.extent_y;
  // Lens shift is a fraction of the fitted extent s on both axes (Blender's convention).
  v.cx = width / 2 - c.shift_x * s * v.fx;
  v.cy = height / 2 + c.shift_y * s * v.fy;
  return v;
}

// Why `v` cannot give usable rays in float, or nullptr: a view plane wider than 1e6 at unit depth
// (a field of view within 0.0002 degrees of 180), degenerate, or not finite.
inline const char* view_plane_problem(const ViewPlane& v, const fb_camera_setup& c) {
  constexpr double kWidest = 1e6;
  if (!(v.extent_x > 0 && v.extent_x <= kWidest && v.extent_y > 0 && v.extent_y <= kWidest))
    return "the view plane is degenerate or too wide to trace in float (check focal length, "
           "sensor, ortho scale and aspect)";
  if (!(std::abs(v.cx) <= kWidest * c.image_width_px &&
        std::abs(v.cy) <= kWidest * c.image_height_px))
    return "the lens shift is not finite or too large";
  return nullptr;
}

}  // namespace fb
