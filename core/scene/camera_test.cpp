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

}  // namespace
}  // namespace fb
