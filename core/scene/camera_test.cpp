// Blender's view plane and the quantities `filmback info` reports, against the closed forms in
// shared notes/blender-camera.md (measured on Blender 3.4) and alpha = 2 atan(h / 2f).
#include "core/scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <filmback/camera_projection.h>

namespace fb {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

double fov_deg(double side_mm, double focal_mm) {
  return 2 * std::atan(side_mm / (2 * focal_mm)) * kDeg;
}

PhysicalCamera camera(double focal_mm, uint32_t fit = FB_SENSOR_FIT_AUTO) {
  PhysicalCamera c;
  c.focal_length_mm = focal_mm;
  c.sensor_fit = fit;
  return c;
}

TEST(CameraQuantities, LandscapeAutoFitSpansTheSensorWidthAcross) {
  const CameraQuantities q = describe_camera(camera(50), 1920, 1080);
  EXPECT_TRUE(q.horizontal_fit);
  EXPECT_NEAR(q.horizontal_fov_deg, fov_deg(36, 50), 1e-12);
  EXPECT_NEAR(q.vertical_fov_deg, fov_deg(36 * 1080.0 / 1920, 50), 1e-12);
  EXPECT_NEAR(q.equivalent_35mm_width_mm, 50, 1e-12);
  EXPECT_NEAR(q.equivalent_35mm_diagonal_mm, 50 * std::hypot(36, 24) / std::hypot(36, 20.25),
              1e-12);
}

TEST(CameraQuantities, PortraitAutoFitPutsTheSensorWidthAlongTheHeight) {
  const CameraQuantities q = describe_camera(camera(35), 1080, 1920);
  EXPECT_FALSE(q.horizontal_fit);
  EXPECT_NEAR(q.vertical_fov_deg, fov_deg(36, 35), 1e-12);
  EXPECT_NEAR(q.horizontal_fov_deg, fov_deg(36 * 1080.0 / 1920, 35), 1e-12);
}

TEST(CameraQuantities, VerticalFitUsesTheSensorHeight) {
  const CameraQuantities q = describe_camera(camera(85, FB_SENSOR_FIT_VERTICAL), 1920, 1080);
  EXPECT_NEAR(q.vertical_fov_deg, fov_deg(24, 85), 1e-12);
  EXPECT_NEAR(q.imaged_sensor_height_mm, 24, 1e-12);
  EXPECT_NEAR(q.imaged_sensor_width_mm, 24 * 1920.0 / 1080, 1e-12);
}

TEST(ViewPlane, ShiftIsAFractionOfTheFittedSideOnBothAxes) {
  PhysicalCamera c = camera(50);
  c.shift_x = 0.1;
  c.shift_y = -0.05;
  const ViewPlane v = view_plane(make_camera_setup(c, 1920, 1080));
  // Horizontal fit: cx = W/2 - shift_x W, cy = H/2 + shift_y W (shift_y in image widths).
  EXPECT_NEAR(v.cx, 960 - 0.1 * 1920, 1e-9);
  EXPECT_NEAR(v.cy, 540 + -0.05 * 1920, 1e-9);
  EXPECT_NEAR(v.fx, 1920 * 50 / 36.0, 1e-9);
  EXPECT_NEAR(v.fy, v.fx, 1e-9);  // square pixels
}

TEST(ViewPlane, OrthographicScaleSpansTheFittedSide) {
  PhysicalCamera c;
  c.projection = FB_PROJECTION_ORTHOGRAPHIC;
  c.ortho_scale_m = 8;
  const ViewPlane v = view_plane(make_camera_setup(c, 400, 200));
  EXPECT_NEAR(v.extent_x, 8, 1e-12);
  EXPECT_NEAR(v.extent_y, 4, 1e-12);
  EXPECT_NEAR(v.fx, 50, 1e-12);
}

// Blender 3.4's exported yfov for every orientation and fit (shared notes/blender-camera.md, table
// "What the Blender 3.4 glTF exporter writes"), measured against Blender's own renders: the
// vertical field of view that the view plane must reproduce.
double blender_yfov(double sensor_w, double sensor_h, double lens, uint32_t fit, double aspect) {
  const bool landscape = aspect >= 1;
  if (fit == FB_SENSOR_FIT_VERTICAL) return 2 * std::atan(sensor_h / (2 * lens));
  if (landscape || fit == FB_SENSOR_FIT_HORIZONTAL)
    return 2 * std::atan(sensor_w / (2 * lens * aspect));
  return 2 * std::atan(sensor_w / (2 * lens));  // portrait, AUTO: the width spans the height
}

struct Shot {
  uint32_t width, height, fit;
  double shift_x, shift_y;
};

class EveryFitOrientationAndShift : public ::testing::TestWithParam<Shot> {};

TEST_P(EveryFitOrientationAndShift, ProjectsKnownPointsAsBlenderDoes) {
  const Shot shot = GetParam();
  PhysicalCamera c;
  c.focal_length_mm = 28;
  c.sensor_width_mm = 36;
  c.sensor_height_mm = 24;
  c.sensor_fit = shot.fit;
  c.shift_x = shot.shift_x;
  c.shift_y = shot.shift_y;
  const double aspect = double(shot.width) / shot.height;
  const double yfov = blender_yfov(36, 24, 28, shot.fit, aspect);
  const CameraQuantities q = describe_camera(c, shot.width, shot.height);
  EXPECT_NEAR(q.vertical_fov_deg, yfov * kDeg, 1e-9);
  EXPECT_NEAR(std::tan(q.horizontal_fov_deg / 2 / kDeg), std::tan(yfov / 2) * aspect, 1e-12);

  // Independently: the unshifted view plane spans 2 tan(yfov/2) vertically; Blender moves it by
  // shift times the fitted extent s (notes: cx = W/2 - shift_x s fx, cy = H/2 + shift_y s fy).
  const double tan_y = std::tan(yfov / 2), tan_x = tan_y * aspect;
  const bool horizontal =
      shot.fit == FB_SENSOR_FIT_AUTO ? aspect >= 1 : shot.fit == FB_SENSOR_FIT_HORIZONTAL;
  const double s = horizontal ? 2 * tan_x : 2 * tan_y;
  const ViewPlane v = view_plane(make_camera_setup(c, shot.width, shot.height));
  for (Vec3d p : {Vec3d{0.3, -0.2, -2}, Vec3d{-1.5, 0.9, -3}, Vec3d{0, 0, -7}}) {
    const double u = p.x / -p.z - shot.shift_x * s, w = p.y / -p.z - shot.shift_y * s;
    const double expected_x = shot.width * (0.5 + u / (2 * tan_x));
    const double expected_y = shot.height * (0.5 - w / (2 * tan_y));
    EXPECT_NEAR(v.cx + v.fx * p.x / -p.z, expected_x, 1e-6);
    EXPECT_NEAR(v.cy - v.fy * p.y / -p.z, expected_y, 1e-6);
  }
}

INSTANTIATE_TEST_SUITE_P(Blender, EveryFitOrientationAndShift,
                         ::testing::Values(Shot{1920, 1080, FB_SENSOR_FIT_AUTO, 0, 0},
                                           Shot{1920, 1080, FB_SENSOR_FIT_AUTO, 0.1, -0.07},
                                           Shot{1920, 1080, FB_SENSOR_FIT_HORIZONTAL, 0.2, 0.05},
                                           Shot{1920, 1080, FB_SENSOR_FIT_VERTICAL, 0, 0},
                                           Shot{1920, 1080, FB_SENSOR_FIT_VERTICAL, -0.1, 0.3},
                                           Shot{1080, 1920, FB_SENSOR_FIT_AUTO, 0, 0},
                                           Shot{1080, 1920, FB_SENSOR_FIT_AUTO, 0.15, 0.1},
                                           Shot{1080, 1920, FB_SENSOR_FIT_HORIZONTAL, 0, -0.2},
                                           Shot{1080, 1920, FB_SENSOR_FIT_VERTICAL, -0.05, 0.05},
                                           Shot{500, 500, FB_SENSOR_FIT_AUTO, 0.5, 0.5}));

}  // namespace
}  // namespace fb
