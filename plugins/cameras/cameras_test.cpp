// Camera plugins through the ABI: rays through raster points re-project onto them, and clipping
// is by depth along the view axis (Blender's clip_start/clip_end), not by distance along the ray.
#include <gtest/gtest.h>

#include <cmath>

#include <filmback/camera_projection.h>
#include <filmback/lens_distortion.h>

#include "core/plugin/instances.h"
#include "core/scene/camera.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::generate_ray;
using test::make_camera;

TEST(PerspectiveCamera, RaysReprojectOntoTheirRasterPoints) {
  PhysicalCamera physical;
  physical.focal_length_mm = 24;
  physical.shift_x = 0.07;
  physical.shift_y = -0.03;
  physical.clip_near_m = 0.5;
  physical.clip_far_m = 40;
  const fb_camera_setup setup = make_camera_setup(physical, 640, 360);
  const auto camera = make_camera("perspective", setup);
  EXPECT_EQ(camera->needs(), 0u);  // a pinhole draws neither lens nor time samples
  const ViewPlane v = view_plane(setup);
  for (auto [x, y] :
       {std::pair{0.f, 0.f}, {640.f, 360.f}, {17.25f, 300.5f}, {float(v.cx), float(v.cy)}}) {
    const fb_camera_ray ray = generate_ray(*camera, x, y);
    const double dx = ray.direction[0], dy = ray.direction[1], dz = ray.direction[2];
    EXPECT_NEAR(std::hypot(dx, dy, dz), 1.0, 1e-6);
    EXPECT_NEAR(v.cx + v.fx * dx / -dz, x, 1e-4);
    EXPECT_NEAR(v.cy - v.fy * dy / -dz, y, 1e-4);
    EXPECT_NEAR(ray.t_min * -dz, 0.5, 1e-6);  // depth along the view axis
    EXPECT_NEAR(ray.t_max * -dz, 40, 1e-5);
    EXPECT_EQ(ray.weight, 1.f);
  }
}

TEST(OrthographicCamera, RaysAreParallelAndSpacedByTheOrthoScale) {
  PhysicalCamera physical;
  physical.projection = FB_PROJECTION_ORTHOGRAPHIC;
  physical.ortho_scale_m = 6;
  physical.clip_near_m = 0;
  physical.clip_far_m = 100;
  const auto camera = make_camera("orthographic", make_camera_setup(physical, 300, 150));
  const fb_camera_ray left = generate_ray(*camera, 0, 75), right = generate_ray(*camera, 300, 0);
  EXPECT_NEAR(left.origin[0], -3, 1e-6);
  EXPECT_NEAR(right.origin[0], 3, 1e-6);
  EXPECT_NEAR(right.origin[1], 1.5, 1e-6);  // the height spans 6 * 150 / 300 m
  EXPECT_EQ(left.direction[2], -1.f);
}

// What `filmback info` prints of a thin lens (fb_camera_api::describe): 50 mm at f/2 is 25 mm
// across; focused at 1 m, 1/f' = 1/1000 + 1/50 gives f' = 47.619 mm.
TEST(ThinLensCamera, DescribesItsApertureAndEffectiveFocalLength) {
  auto library = test::loader().load(FB_KIND_CAMERA, "thinlens");
  const BoundParams params(library->descriptor(), {{"fstop", "2"}, {"focus_distance_m", "1"}});
  const CameraInstance camera(library, params, make_camera_setup(PhysicalCamera{}, 10, 10));
  const std::string text = camera.describe();
  EXPECT_NE(text.find("aperture diameter: 25 mm (f/2)"), std::string::npos) << text;
  EXPECT_NE(text.find("effective focal length: 47.619 mm"), std::string::npos) << text;
  EXPECT_EQ(make_camera("perspective", make_camera_setup(PhysicalCamera{}, 10, 10))->describe(),
            "");
}

TEST(CameraPlugins, RefuseTheOtherProjection) {
  PhysicalCamera physical;
  physical.projection = FB_PROJECTION_ORTHOGRAPHIC;
  EXPECT_THROW(make_camera("perspective", make_camera_setup(physical, 10, 10)), std::runtime_error);
}

// A tracked clip's distortion (filmback/lens_distortion.h): both projective cameras aim each film
// position's ray through its undistorted position, and a position beyond the model's fold is
// black (weight 0) along a finite ray. k1 = -0.5 folds at a normalized radius of 0.544: the
// corners of this 128x80 frame (r = 0.76 through f = 199 px on the 256x160 clip) are beyond it.
TEST(CameraPlugins, ApplyATrackedLensDistortionBeforeTheirProjection) {
  PhysicalCamera physical;
  physical.focal_length_mm = 28;
  const fb_camera_setup setup = make_camera_setup(physical, 128, 80);
  const ViewPlane v = view_plane(setup);
  const std::vector<std::pair<std::string, std::string>> distortion = {
      {"polynomial_k1", "-0.5"},      {"clip_width_px", "256"},
      {"clip_height_px", "160"},      {"clip_focal_length_px", "199.1"},
      {"clip_principal_x_px", "131"}, {"clip_principal_y_px", "77.5"}};
  LensDistortionParams params;
  params.polynomial_k = {-0.5, 0, 0};
  params.clip_width_px = 256;
  params.clip_height_px = 160;
  params.focal_length_px = 199.1;
  params.principal_px = {131, 77.5};
  const LensDistortion lens(params);
  for (const char* name : {"perspective", "thinlens"}) {
    SCOPED_TRACE(name);
    auto settings = distortion;
    if (std::string(name) == "thinlens") settings.push_back({"fstop", "1e6"});  // a pinhole's rays
    auto library = test::loader().load(FB_KIND_CAMERA, name);
    const CameraInstance camera(library, BoundParams(library->descriptor(), settings), setup);
    for (auto [x, y] : {std::pair{20.f, 15.f}, {100.5f, 70.25f}, {110.f, 20.f}}) {
      const fb_camera_ray ray = generate_ray(camera, x, y);
      const Vec2d expected = *lens.undistorted_film({x, y}, 128, 80);
      const double dx = ray.direction[0], dy = ray.direction[1], dz = ray.direction[2];
      EXPECT_NEAR(v.cx + v.fx * dx / -dz, expected.x, 2e-4);
      EXPECT_NEAR(v.cy - v.fy * dy / -dz, expected.y, 2e-4);
      EXPECT_GT(std::hypot(expected.x - x, expected.y - y), 0.05);  // the distortion moves it
      EXPECT_EQ(ray.weight, 1.f);
    }
    const fb_camera_ray corner = generate_ray(camera, 0.5f, 0.5f);
    EXPECT_EQ(corner.weight, 0.f);
    for (float c : corner.direction)
      EXPECT_TRUE(std::isfinite(c));
  }
}

}  // namespace
}  // namespace fb
