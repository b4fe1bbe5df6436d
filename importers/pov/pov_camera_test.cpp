// POV-Ray's camera rules (importers/pov/pov_camera.h) one by one, and the converted camera's rays
// through the camera plugins against POV-Ray's own ray construction. The renders that confirm
// these rules against POV-Ray itself are tests/pov/pov_camera_alignment_test.cpp.
#include "importers/pov/pov_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

#include <filmback/camera_projection.h>

#include "core/util/error.h"
#include "importers/pov/pov_importer.h"
#include "importers/pov/pov_space.h"
#include "support/pov_rays.h"

namespace fb::pov {
namespace {

constexpr double kDegrees = 180 / std::numbers::pi;

void expect_near(Vec3d a, Vec3d b, double tolerance, const char* what) {
  EXPECT_NEAR(a.x, b.x, tolerance) << what;
  EXPECT_NEAR(a.y, b.y, tolerance) << what;
  EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

PovCameraVectors evaluate(const CameraStatement& s) {
  Diagnostics diagnostics;
  return evaluate_camera(s, diagnostics);
}

// Every converted camera must give POV-Ray's rays: same origin, same direction, for raster points
// over the whole image (corners, centre, off-centre), through the plugin filmback renders with.
void expect_povray_rays(const CameraStatement& s, uint32_t width, uint32_t height,
                        double tolerance = 2e-6, bool same_line = false) {
  Diagnostics diagnostics;
  const PovCameraVectors vectors = evaluate_camera(s, diagnostics);
  const PovCamera camera = convert_camera(s, width, height, diagnostics);
  const auto plugin = test::make_camera_plugin(camera, width, height);
  for (const auto& [x, y] : {std::pair{0.0, 0.0},
                             {double(width), double(height)},
                             {double(width), 0.0},
                             {width / 2.0, height / 2.0},
                             {17.25, 3.5}}) {
    const test::WorldRay pov = test::pov_ray(vectors, x, y, width, height);
    // Lens (0.5, 0.5) is the centre of the thin lens: its chief ray.
    const test::WorldRay ours =
        test::filmback_ray(*plugin, camera.camera, {float(x), float(y), 0.5f, 0.5f, 0.f});
    const double scale = std::max(1.0, length(pov.origin));
    expect_near(ours.direction, pov.direction, tolerance, "direction");
    // An orthographic camera's rays may start elsewhere on the same line (an oblique direction).
    const Vec3d offset = ours.origin - pov.origin;
    expect_near(same_line ? offset - pov.direction * dot(offset, pov.direction) : offset, {0, 0, 0},
                tolerance * scale, "origin");
  }
}

TEST(PovCamera, DefaultCameraHasRight133) {
  const CameraStatement defaults;
  const PovCameraVectors v = evaluate(defaults);
  expect_near(v.location, {0, 0, 0}, 0, "location");
  expect_near(v.direction, {0, 0, 1}, 0, "direction");
  expect_near(v.right, {1.33, 0, 0}, 0, "right");
  expect_near(v.up, {0, 1, 0}, 0, "up");
  EXPECT_FALSE(v.focal_blur);

  Diagnostics diagnostics;
  const PovCamera c = convert_camera(std::nullopt, 160, 120, diagnostics);
  EXPECT_EQ(diagnostics.count(), 0u);
  // 1.33 wide, 1 high at distance 1: 67.248 degrees, not 4/3's 67.380; pixels 0.9975 wide at 4:3.
  const CameraQuantities q = describe_camera(c.camera.physical, 160, 120);
  EXPECT_NEAR(q.horizontal_fov_deg, 2 * std::atan(0.665) * kDegrees, 1e-9);
  EXPECT_NEAR(q.horizontal_fov_deg, 67.248, 5e-4);
  EXPECT_NEAR(c.pixel_aspect, 1.33 * 120 / 160, 1e-12);
  const ViewPlane plane =
      view_plane(make_camera_setup(c.camera.physical, 160, 120, c.pixel_aspect));
  EXPECT_NEAR(plane.extent_x, 1.33, 1e-12);
  EXPECT_NEAR(plane.extent_y, 1.0, 1e-12);
  // POV-Ray looks down +z of its left-handed space: our -z, so the camera is not rotated.
  expect_near(c.camera.world_from_camera.vector({0, 0, -1}), {0, 0, -1}, 1e-15, "view axis");
  expect_near(c.camera.world_from_camera.vector({1, 0, 0}), {1, 0, 0}, 1e-15, "right axis");
  expect_povray_rays(defaults, 160, 120);
}

TEST(PovCamera, AngleRescalesDirectionFromTheLengthOfRight) {
  for (const double angle : {30.0, 60.0, 100.0}) {
    CameraStatement s;
    s.angle_deg = angle;
    s.direction = {0, 0, 3};  // only its direction survives
    s.up = {0, 5, 0};         // plays no part
    s.right = {2, 0, 0};
    const PovCameraVectors v = evaluate(s);
    EXPECT_NEAR(length(v.direction), 2 / (2 * std::tan(angle / 2 / kDegrees)), 1e-12) << angle;
    EXPECT_NEAR(v.focal_distance, length(v.direction), 1e-12);  // Direction_Length follows angle
    Diagnostics diagnostics;
    const CameraQuantities q =
        describe_camera(convert_camera(s, 200, 100, diagnostics).camera.physical, 200, 100);
    EXPECT_NEAR(q.horizontal_fov_deg, angle, 1e-9);
    expect_povray_rays(s, 200, 100);
  }
}

TEST(PovCamera, AngleOf180OrMoreIsAnError) {
  CameraStatement s;
  s.where = {"scene.pov", 4, 10};
  s.angle_deg = 180;
  Diagnostics diagnostics;
  try {
    evaluate_camera(s, diagnostics);
    FAIL() << "angle 180 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.pov:4:10: camera angle: viewing angle"),
              std::string::npos)
        << e.what();
  }
}

TEST(PovCamera, LookAtKeepsLengthsAndRebuildsTheBasisFromSky) {
  CameraStatement s;
  s.location = {0, 0, -10};
  s.look_at = Vec3d{1, 2, 3};
  s.direction = {0, 0, 2};
  s.right = {1.6, 0, 0};
  s.up = {0, 1.2, 0};
  const PovCameraVectors v = evaluate(s);
  const Vec3d d = normalize(Vec3d{1, 2, 13});
  const Vec3d r = normalize(cross(Vec3d{0, 1, 0}, d));
  expect_near(v.direction, d * 2, 1e-12, "direction");
  expect_near(v.right, r * 1.6, 1e-12, "right");
  expect_near(v.up, cross(d, r) * 1.2, 1e-12, "up");
  EXPECT_NEAR(v.right.y, 0, 1e-15);  // the default sky keeps the horizon level
  expect_povray_rays(s, 160, 120);

  s.sky = {1, 1, 0};  // a tilted sky rolls the camera
  const PovCameraVectors tilted = evaluate(s);
  EXPECT_GT(std::abs(tilted.right.y), 0.1);
  expect_near(tilted.right, normalize(cross(s.sky, d)) * 1.6, 1e-12, "tilted right");
  expect_povray_rays(s, 160, 120);
}

TEST(PovCamera, LookAtAtTheLocationIsAnError) {
  CameraStatement s;
  s.location = {1, 2, 3};
  s.look_at = Vec3d{1, 2, 3};
  EXPECT_THROW(evaluate(s), InputError);
}

TEST(PovCamera, LookingAlongSkyKeepsTheGivenRight) {
  CameraStatement s;
  s.location = {0, 10, 0};
  s.look_at = Vec3d{0, 0, 0};
  Diagnostics diagnostics;
  const PovCameraVectors v = evaluate_camera(s, diagnostics);
  EXPECT_EQ(diagnostics.count(), 1u);
  expect_near(v.right, {1.33, 0, 0}, 1e-12, "right");
  // up = direction x right: +z at the top of the image (pitfall 6 of the notes).
  expect_near(normalize(v.up), {0, 0, 1}, 1e-12, "up");
  expect_povray_rays(s, 160, 120);
}

TEST(PovCamera, HandednessDecidesTheMirror) {
  // cornell.pov: a negative right without look_at mirrors the image.
  CameraStatement mirrored;
  mirrored.right = {-1.33, 0, 0};
  Diagnostics diagnostics;
  const PovCamera m = convert_camera(mirrored, 160, 120, diagnostics);
  EXPECT_LT(m.camera.world_from_camera.determinant3x3(), 0);
  expect_povray_rays(mirrored, 160, 120);

  // benchmark.pov: direction y, sky z, up z, right -x: (up x direction) . right > 0, so with
  // look_at it is not mirrored, though right is negative.
  CameraStatement benchmark;
  benchmark.direction = {0, 1, 0};
  benchmark.sky = {0, 0, 1};
  benchmark.up = {0, 0, 1};
  benchmark.right = {-4.0 / 3, 0, 0};
  benchmark.location = {0.5, -4, 3};
  benchmark.look_at = Vec3d{0, 0, 0.5};
  EXPECT_GT(dot(cross(benchmark.up, benchmark.direction), benchmark.right), 0);
  const PovCamera b = convert_camera(benchmark, 160, 120, diagnostics);
  EXPECT_GT(b.camera.world_from_camera.determinant3x3(), 0);
  expect_povray_rays(benchmark, 160, 120);

  // The same with right +x has negative handedness: look_at mirrors it.
  benchmark.right = {4.0 / 3, 0, 0};
  EXPECT_LT(
      convert_camera(benchmark, 160, 120, diagnostics).camera.world_from_camera.determinant3x3(),
      0);
  expect_povray_rays(benchmark, 160, 120);
  EXPECT_EQ(diagnostics.count(), 0u);
}

TEST(PovCamera, MismatchedAspectGivesNonSquarePixels) {
  CameraStatement s;
  s.right = {1, 0, 0};  // a square view ...
  s.up = {0, 1, 0};
  Diagnostics diagnostics;
  const PovCamera c = convert_camera(s, 200, 100, diagnostics);  // ... on a 2:1 image
  EXPECT_NEAR(c.pixel_aspect, 0.5, 1e-12);
  const ViewPlane plane = view_plane(make_camera_setup(c.camera.physical, 200, 100, 0.5));
  EXPECT_NEAR(plane.extent_x, 1, 1e-12);
  EXPECT_NEAR(plane.extent_y, 1, 1e-12);
  expect_povray_rays(s, 200, 100);

  // Portrait: right x*image_width/image_height keeps pixels square and angle horizontal.
  s.right = {90.0 / 160, 0, 0};
  s.angle_deg = 50;
  const PovCamera portrait = convert_camera(s, 90, 160, diagnostics);
  EXPECT_NEAR(portrait.pixel_aspect, 1, 1e-12);
  EXPECT_NEAR(describe_camera(portrait.camera.physical, 90, 160).horizontal_fov_deg, 50, 1e-9);
  expect_povray_rays(s, 90, 160);
}

TEST(PovCamera, DirectionNotPerpendicularBecomesALensShift) {
  CameraStatement s;
  s.direction = {0.2, -0.1, 1};
  Diagnostics diagnostics;
  const PovCamera c = convert_camera(s, 160, 120, diagnostics);
  EXPECT_EQ(diagnostics.count(), 0u) << "exact: no warning";
  EXPECT_NEAR(c.camera.physical.shift_x, 0.2 / 1.33, 1e-12);
  EXPECT_NEAR(c.camera.physical.shift_y, -0.1 / 1.33, 1e-12);
  expect_povray_rays(s, 160, 120);
}

TEST(PovCamera, RightNotPerpendicularToUpIsWarnedWithItsError) {
  CameraStatement s;
  s.up = {0.1, 1, 0};
  Diagnostics diagnostics;
  const PovCamera c = convert_camera(s, 160, 120, diagnostics);
  ASSERT_EQ(diagnostics.count(), 1u);
  // 0.5 * 0.1 / 1.33 of the width: 6.015 px at the top and bottom edges.
  EXPECT_NE(diagnostics.messages()[0].find("6.01504 px"), std::string::npos)
      << diagnostics.messages()[0];
  // The error is what the message says: the rays of the top edge's centre are 6 px apart.
  const PovCameraVectors v = evaluate(s);
  const auto plugin = test::make_camera_plugin(c, 160, 120);
  const test::WorldRay pov = test::pov_ray(v, 80, 0, 160, 120);
  const test::WorldRay ours = test::filmback_ray(*plugin, c.camera, {80.f, 0.f, 0.f, 0.f, 0.f});
  // Where POV-Ray's ray crosses the view plane z = -1 (world), in pixels of 1.33 / 160 m.
  const double pov_x = pov.direction.x / -pov.direction.z,
               our_x = ours.direction.x / -ours.direction.z;
  EXPECT_NEAR(std::abs(pov_x - our_x) * 160 / 1.33, 6.01504, 1e-4);
}

TEST(PovCamera, TransformsApplyLastWhateverTheirPlace) {
  CameraStatement s;
  s.location = {0, 1, -5};
  s.look_at = Vec3d{0, 1, 0};
  s.angle_deg = 60;
  s.transform = Transform::translate({2, 0, 0}) * test::pov_rotate({0, 30, 0});
  const PovCameraVectors v = evaluate(s);
  CameraStatement plain = s;
  plain.transform = Transform();
  const PovCameraVectors u = evaluate(plain);
  expect_near(v.location, s.transform.point(u.location), 1e-12, "location");
  expect_near(v.direction, s.transform.vector(u.direction), 1e-12, "direction");
  expect_near(v.right, s.transform.vector(u.right), 1e-12, "right");
  // rotate y*30 maps +z towards +x (left-handed rotation seen from above): the view turns right.
  EXPECT_GT(v.direction.x, 0);
  expect_povray_rays(s, 160, 120);

  // A non-uniform scale changes the field of view: right grows, direction does not.
  s.transform = Transform::scale({2, 1, 1});
  plain.location = {0, 0, -5};
  plain.look_at = Vec3d{0, 0, 0};
  plain.transform = s.transform;
  const PovCameraVectors scaled = evaluate(plain);
  EXPECT_NEAR(length(scaled.right), 2 * 1.33, 1e-12);
  expect_povray_rays(plain, 160, 120);
}

TEST(PovCamera, OrthographicSizes) {
  CameraStatement s;
  s.type = CameraType::kOrthographic;
  s.location = {0, 0, -10};
  s.look_at = Vec3d{0, 0, 0};
  // Neither right nor up: the area a perspective camera sees in the plane through look_at.
  PovCameraVectors v = evaluate(s);
  EXPECT_NEAR(length(v.right), 13.3, 1e-12);
  EXPECT_NEAR(length(v.up), 10, 1e-12);
  Diagnostics diagnostics;
  PovCamera c = convert_camera(s, 160, 120, diagnostics);
  EXPECT_EQ(c.camera.physical.projection, uint32_t(FB_PROJECTION_ORTHOGRAPHIC));
  EXPECT_NEAR(c.camera.physical.ortho_scale_m, 13.3, 1e-12);
  expect_povray_rays(s, 160, 120);

  // right and up given: exactly that many units.
  s.right = {4, 0, 0};
  s.up = {0, 3, 0};
  s.right_given = s.up_given = true;
  v = evaluate(s);
  EXPECT_NEAR(length(v.right), 4, 1e-12);
  EXPECT_NEAR(length(v.up), 3, 1e-12);
  expect_povray_rays(s, 160, 120);

  // ... unless angle is given: width 2 |look_at - location| tan(angle / 2).
  s.angle_deg = 40;
  v = evaluate(s);
  EXPECT_NEAR(length(v.right), 2 * 10 * std::tan(20 / kDegrees), 1e-12);
  expect_povray_rays(s, 160, 120);

  // A direction tilted towards right (no look_at): rays along it through the same points of the
  // view. Tilted towards right and up at once, right and up seen along it are skewed: a warning.
  CameraStatement oblique;
  oblique.type = CameraType::kOrthographic;
  oblique.direction = {0.3, 0, 1};
  oblique.right = {4, 0, 0};
  oblique.up = {0, 3, 0};
  oblique.right_given = oblique.up_given = true;
  Diagnostics quiet;
  convert_camera(oblique, 160, 120, quiet);
  EXPECT_EQ(quiet.count(), 0u) << "exact: no warning";
  expect_povray_rays(oblique, 160, 120, 2e-6, true);
  oblique.direction = {0.3, -0.2, 1};
  convert_camera(oblique, 160, 120, quiet);
  EXPECT_EQ(quiet.count(), 1u);

  // Without look_at the distance is to POV-Ray's internal look_at <0, 0, 1>.
  CameraStatement no_look_at;
  no_look_at.type = CameraType::kOrthographic;
  no_look_at.location = {0, 0, -4};
  EXPECT_NEAR(length(evaluate(no_look_at).right), 1.33 * 5, 1e-12);
  expect_povray_rays(no_look_at, 160, 120);
}

TEST(PovCamera, FocalBlurIsAThinLensOfRadiusAperture4) {
  CameraStatement s;
  s.location = {0, 0, -10};
  s.look_at = Vec3d{0, 0, 0};
  s.angle_deg = 45;
  s.aperture = 0.5;
  s.blur_samples = 20;
  s.focal_point = Vec3d{3, 0, -8};
  Diagnostics diagnostics;
  const PovCamera c = convert_camera(s, 160, 120, diagnostics);
  const PhysicalCamera& p = c.camera.physical;
  ASSERT_TRUE(p.has_aperture());
  EXPECT_NEAR(p.focal_length_mm * 1e-3 / (2 * p.fstop), 0.125, 1e-12);  // lens radius, m
  // The focal plane at the Euclidean distance to focal_point, not its depth 2.
  EXPECT_NEAR(p.focus_distance_m, std::sqrt(13.0), 1e-12);
  expect_povray_rays(s, 160, 120);

  // Every lens ray of a pixel passes where POV-Ray's do (JitterCameraRay): through the point
  // (F / |D|) (D + x0 R + y0 U) from the location, leaving the lens disc of radius aperture / 4
  // perpendicular to the view.
  const PovCameraVectors v = evaluate(s);
  const auto plugin = test::make_camera_plugin(c, 160, 120);
  const double x = 40.25, y = 100.5;
  const Vec3d focus = world_from_pov(
      v.location + (v.direction + v.right * (x / 160 - 0.5) + v.up * (0.5 - y / 120)) *
                       (v.focal_distance / length(v.direction)));
  const Vec3d axis = normalize(world_from_pov(v.direction));
  for (const auto& [u, w] : {std::pair{0.1f, 0.3f}, {0.9f, 0.7f}, {0.99f, 0.5f}, {0.5f, 0.02f}}) {
    const test::WorldRay ray =
        test::filmback_ray(*plugin, c.camera, {float(x), float(y), u, w, 0.f});
    const Vec3d lens = ray.origin - world_from_pov(v.location);
    EXPECT_LT(length(lens), 0.125 + 1e-6);
    EXPECT_NEAR(dot(lens, axis), 0, 1e-6);
    const Vec3d to_focus = focus - ray.origin;
    EXPECT_LT(length(to_focus - ray.direction * dot(to_focus, ray.direction)), 1e-5)
        << "lens sample (" << u << ", " << w << ")";
  }

  // Without focal_point: Parse_Camera's Direction_Length, 1 unless angle or look_at set it.
  CameraStatement plain;
  plain.direction = {0, 0, 3};
  plain.aperture = 1;
  plain.blur_samples = 10;
  EXPECT_NEAR(convert_camera(plain, 160, 120, diagnostics).camera.physical.focus_distance_m, 1,
              1e-12);
  plain.look_at = Vec3d{0, 0, 5};
  EXPECT_NEAR(convert_camera(plain, 160, 120, diagnostics).camera.physical.focus_distance_m, 3,
              1e-12);
  // No blur_samples: no blur.
  plain.blur_samples = 0;
  EXPECT_FALSE(convert_camera(plain, 160, 120, diagnostics).camera.physical.has_aperture());
}

// The other camera types (plugins/cameras/pov_*) against POV-Ray's ray formula (support/pov_rays,
// written from CreateCameraRay in POV-Ray's space): at every raster point of a 13 x 11 grid over
// the image, edges included, and at points just inside and outside a fisheye's circle, the same
// weight (traced or not), and for traced ones the same origin and direction. Every ray is finite.
void expect_projection_rays(const CameraStatement& s, uint32_t width, uint32_t height) {
  Diagnostics diagnostics;
  const PovCameraVectors vectors = evaluate_camera(s, diagnostics);
  const PovCamera camera = convert_camera(s, width, height, diagnostics);
  EXPECT_EQ(diagnostics.count(), 0u) << diagnostics.messages().front();
  ASSERT_EQ(camera.camera.physical.projection, uint32_t(FB_PROJECTION_PANORAMIC));
  const auto plugin = test::make_camera_plugin(camera, width, height);
  int traced = 0, points = 0;
  for (int j = 0; j <= 10; ++j)
    for (int i = 0; i <= 12; ++i) {
      // The plugin's raster points are floats: POV-Ray's ray at the same float.
      const double x = float(width * i / 12.0), y = float(height * j / 10.0);
      const test::WorldRay pov = test::pov_ray(vectors, x, y, width, height);
      const test::WorldRay ours =
          test::filmback_ray(*plugin, camera.camera, {float(x), float(y), 0.5f, 0.5f, 0.f});
      SCOPED_TRACE(testing::Message() << "raster point (" << x << ", " << y << ")");
      ++points;
      ASSERT_TRUE(is_finite(ours.origin) && is_finite(ours.direction));
      EXPECT_NEAR(length(ours.direction), 1, 1e-6);
      EXPECT_EQ(ours.weight, pov.weight);
      if (pov.weight == 0 || ours.weight == 0) continue;
      ++traced;
      expect_near(ours.direction, pov.direction, 2e-6, "direction");
      expect_near(ours.origin, pov.origin, 2e-6 * std::max(1.0, length(pov.origin)), "origin");
    }
  EXPECT_GT(traced, points / 3) << "a fisheye's circle and more of the image is traced";
}

CameraStatement projection(CameraType type, std::optional<double> angle = std::nullopt) {
  CameraStatement s;
  s.type = type;
  s.where = {"scene.pov", 7, 1};
  s.angle_deg = angle;
  if (angle) s.angle_where = {"scene.pov", 9, 3};
  return s;
}

// A camera placed and turned every way the rules allow: look_at with a tilted sky, a rotation and
// a translation, and vectors of unusual lengths (the types use |right| and |up| differently).
CameraStatement posed(CameraStatement s) {
  s.location = {1, 2, -6};
  s.look_at = Vec3d{0.5, 0, 1};
  s.sky = {0.2, 1, 0};
  s.right = {1.6, 0, 0};
  s.up = {0, 1.1, 0};
  s.direction = {0, 0, 1.7};
  s.transform = Transform::translate({0.3, -0.2, 0.5}) * test::pov_rotate({5, 20, -10});
  return s;
}

TEST(PovCamera, ProjectionTypesTracePovRaysRays) {
  const std::pair<CameraType, double> types[] = {
      {CameraType::kFisheye, 180},   {CameraType::kUltraWideAngle, 150},
      {CameraType::kOmnimax, 0},     {CameraType::kPanoramic, 0},
      {CameraType::kSpherical, 360}, {CameraType::kSpherical, 120},
  };
  for (const auto& [type, angle] : types) {
    SCOPED_TRACE(testing::Message() << "type " << int(type) << ", angle " << angle);
    const CameraStatement s = projection(type, angle > 0 ? std::optional(angle) : std::nullopt);
    expect_projection_rays(s, 160, 120);
    expect_projection_rays(posed(s), 160, 120);
    expect_projection_rays(s, 90, 160);  // portrait: the same vectors spread over other pixels
  }
  for (int variant = 1; variant <= 4; ++variant) {
    SCOPED_TRACE(testing::Message() << "cylinder " << variant);
    CameraStatement s = projection(CameraType::kCylinder, 200);
    s.cylinder_type = variant;
    expect_projection_rays(s, 160, 120);
    expect_projection_rays(posed(s), 160, 120);
  }
}

TEST(PovCamera, ProjectionsKeepTheMirror) {
  // Negative handedness (cornell.pov's right -x, no look_at): the linear types mirror with the
  // frame; the spherical camera turns about right and up, and its image is not a mirror image.
  for (const CameraType type : {CameraType::kFisheye, CameraType::kSpherical, CameraType::kCylinder,
                                CameraType::kPanoramic}) {
    SCOPED_TRACE(testing::Message() << "type " << int(type));
    CameraStatement s = projection(type);
    s.cylinder_type = 1;
    s.right = {-1.33, 0, 0};
    expect_projection_rays(s, 160, 120);
    s.right = {1.33, 0, 0};  // benchmark.pov's vectors, with look_at: h < 0
    s.direction = {0, 1, 0};
    s.sky = {0, 0, 1};
    s.up = {0, 0, 1};
    s.location = {0.5, -4, 3};
    s.look_at = Vec3d{0, 0, 0.5};
    expect_projection_rays(s, 160, 120);
  }
}

TEST(PovCamera, ProjectionValuesNameTheirPlaceInTheScene) {
  Diagnostics diagnostics;
  CameraStatement s = projection(CameraType::kFisheye, 180);
  s.right = {1.5, 0, 0};
  PovCamera c = convert_camera(s, 160, 120, diagnostics);
  ASSERT_TRUE(c.camera.model.has_value());
  EXPECT_EQ(c.camera.model->kind, "pov_fisheye");
  EXPECT_EQ(c.camera.model->origin.text(), "scene.pov:7:1: camera type");
  ASSERT_EQ(c.camera.model->numbers.size(), 3u);
  const NamedNumber& angle = c.camera.model->numbers[0];
  EXPECT_EQ(angle.key, "angle_deg");
  EXPECT_EQ(angle.value, 180);
  EXPECT_EQ(angle.origin.text(), "scene.pov:9:3: camera angle");
  EXPECT_EQ(c.camera.model->numbers[1].key, "right_length_m");
  EXPECT_EQ(c.camera.model->numbers[1].value, 1.5);
  EXPECT_EQ(c.camera.model->numbers[1].origin.text(),
            "scene.pov:7:1: camera (|right| after POV-Ray's camera rules)");
  EXPECT_EQ(c.pixel_aspect, 1);

  // Spherical: `angle H` alone gives V = H / 2; no angle, 360 x 180 (Camera::Init).
  s = projection(CameraType::kSpherical, 240);
  c = convert_camera(s, 160, 120, diagnostics);
  ASSERT_EQ(c.camera.model->numbers.size(), 2u);
  EXPECT_EQ(c.camera.model->numbers[1].key, "angle_v_deg");
  EXPECT_EQ(c.camera.model->numbers[1].value, 120);
  EXPECT_EQ(c.camera.model->numbers[1].origin.text(),
            "scene.pov:9:3: camera angle (half the horizontal angle, as POV-Ray)");
  s.angle_deg.reset();
  c = convert_camera(s, 160, 120, diagnostics);
  EXPECT_EQ(c.camera.model->numbers[0].value, 360);
  EXPECT_EQ(c.camera.model->numbers[1].value, 180);
  EXPECT_EQ(c.camera.model->numbers[0].origin.text(),
            "scene.pov:7:1: camera (POV-Ray's default angle)");

  s = projection(CameraType::kCylinder);
  s.cylinder_type = 3;
  c = convert_camera(s, 160, 120, diagnostics);
  EXPECT_EQ(c.camera.model->kind, "pov_cylinder");
  EXPECT_EQ(c.camera.model->numbers[0].key, "variant");
  EXPECT_EQ(c.camera.model->numbers[0].value, 3);
  EXPECT_EQ(c.camera.model->numbers[1].value, 90);  // Camera::Init's angle
  EXPECT_EQ(diagnostics.count(), 0u);
}

// What `filmback info` prints under the plan: each plugin's own derived quantities.
TEST(PovCamera, ProjectionPluginsDescribeTheirFieldOfView) {
  Diagnostics diagnostics;
  const auto describe = [&](const CameraStatement& s) {
    return test::make_camera_plugin(convert_camera(s, 160, 120, diagnostics), 160, 120)->describe();
  };
  // A fisheye's circle is W / |right| px wide and H / |up| high: 160 / 1.33 = 120.301.
  EXPECT_EQ(describe(projection(CameraType::kFisheye, 180)),
            "field of view: 180 deg across the image circle (90 deg from the axis at its edge)\n"
            "image circle: 120.301 px wide, 120 px high, centred; no rays outside it\n");
  EXPECT_EQ(describe(projection(CameraType::kSpherical, 240)),
            "field of view: 240 deg across, 120 deg up; 1.5 x 1 deg a pixel\n");
  CameraStatement cylinder = projection(CameraType::kCylinder, 100);
  cylinder.cylinder_type = 4;
  cylinder.right = {3, 0, 0};
  EXPECT_EQ(describe(cylinder),
            "field of view: 100 deg around the right axis; 3 m along it (rays from a line: "
            "orthographic)\n");
  // ultra_wide_angle spreads angle |up| / |right| up: 133 * 1 / 1.33 = 100.
  EXPECT_EQ(describe(projection(CameraType::kUltraWideAngle, 133)),
            "field of view: 133 deg across, 100 deg up\n");
}

// The message a bad camera statement gives, or "" if it converts.
std::string error_of(const CameraStatement& s) {
  Diagnostics diagnostics;
  try {
    convert_camera(s, 160, 120, diagnostics);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PovCamera, BadProjectionAnglesAndTypesAreErrorsWithTheirPlace) {
  EXPECT_EQ(error_of(projection(CameraType::kFisheye, -10)),
            "scene.pov:9:3: camera angle: negative viewing angle");
  EXPECT_EQ(error_of(projection(CameraType::kSpherical, -10)),
            "scene.pov:9:3: camera angle: negative horizontal angle");
  CameraStatement s = projection(CameraType::kSpherical, 90);
  s.angle_v_deg = -1;
  EXPECT_EQ(error_of(s), "scene.pov:9:3: camera angle: negative vertical angle");
  s.type = CameraType::kFisheye;  // POV-Ray's parser takes a second angle for spherical only
  s.angle_v_deg = 40;
  EXPECT_EQ(error_of(s),
            "scene.pov:9:3: camera angle: a second angle: only a spherical camera takes one "
            "(angle H, V)");
  s = projection(CameraType::kFisheye, std::nan(""));
  EXPECT_EQ(error_of(s), "scene.pov:9:3: camera angle: negative viewing angle");
  for (const int variant : {0, 5, -1}) {
    s = projection(CameraType::kCylinder);
    s.cylinder_type = variant;
    EXPECT_EQ(error_of(s), "scene.pov:7:1: invalid cylinder camera type " +
                               std::to_string(variant) + ": valid are types 1 to 4");
  }
}

// The same errors from a .pov file: the importer names the keyword's line and column.
TEST(PovCamera, BadProjectionsInAFileNameTheirPlace) {
  const std::filesystem::path folder = std::filesystem::path(testing::TempDir()) / "pov_camera";
  std::filesystem::create_directories(folder);
  const auto error_in = [&](const std::string& camera) {
    {
      std::ofstream out(folder / "scene.pov");
      out << "#version 3.7;\ncamera {\n" << camera << "\n}\n";
    }
    Diagnostics diagnostics;
    ImportOptions options;
    options.resolution = {64, 48};
    try {
      import_pov(folder / "scene.pov", options, diagnostics);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_in("  fisheye\n  angle -5"),
            "scene.pov:4:3: camera angle: negative viewing angle");
  EXPECT_EQ(error_in("  spherical location 0\n    angle 90, -1"),
            "scene.pov:4:5: camera angle: negative vertical angle");
  EXPECT_EQ(error_in("  cylinder 7"),
            "scene.pov:2:1: invalid cylinder camera type 7: valid are types 1 to 4");
  EXPECT_EQ(error_in("  cylinder 2 angle 400"), "no error");
}

// Angles of 0, 360 and beyond are POV-Ray's to render (it takes any angle >= 0): rays keep to
// POV-Ray's formula (a fisheye of 360 looks straight back at its rim, 720 wraps round twice), all
// finite, none NaN. The plugins refuse an angle beyond 1e6 degrees, naming its place.
TEST(PovCamera, ExtremeProjectionAnglesStayPovRays) {
  for (const double angle : {0.0, 1e-9, 359.9, 360.0, 720.0, 1000.0, 123456.0}) {
    SCOPED_TRACE(testing::Message() << "angle " << angle);
    for (const CameraType type : {CameraType::kFisheye, CameraType::kUltraWideAngle,
                                  CameraType::kSpherical, CameraType::kCylinder}) {
      CameraStatement s = projection(type, angle);
      s.cylinder_type = 2;
      if (type == CameraType::kSpherical) s.angle_v_deg = angle * 0.7;
      expect_projection_rays(s, 64, 48);
    }
  }
  Diagnostics diagnostics;
  const PovCamera huge = convert_camera(projection(CameraType::kFisheye, 2e6), 64, 48, diagnostics);
  try {
    test::make_camera_plugin(huge, 64, 48);
    FAIL() << "an angle of 2e6 degrees was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.pov:9:3: camera angle: "), std::string::npos)
        << e.what();
  }
}

TEST(PovCamera, ProjectionsWarnWhatTheyCannotRender) {
  CameraStatement s = projection(CameraType::kFisheye, 180);
  s.up = {0, 1, 0.05};  // not perpendicular to direction: 2.86 degrees
  Diagnostics diagnostics;
  convert_camera(s, 160, 120, diagnostics);
  ASSERT_EQ(diagnostics.count(), 1u);
  EXPECT_NE(diagnostics.messages()[0].find("scene.pov:7:1: the camera's direction, right and up "
                                           "vectors are not perpendicular (up to 2.86241 degrees"),
            std::string::npos)
      << diagnostics.messages()[0];

  s = projection(CameraType::kSpherical);
  s.aperture = 0.5;
  s.blur_samples = 10;
  diagnostics = Diagnostics();
  convert_camera(s, 160, 120, diagnostics);
  ASSERT_EQ(diagnostics.count(), 1u);
  EXPECT_NE(diagnostics.messages()[0].find(
                "scene.pov:7:1: unsupported feature 'focal_blur' with a spherical camera"),
            std::string::npos)
      << diagnostics.messages()[0];
}

TEST(PovCamera, DegenerateVectorsAreAnError) {
  CameraStatement s;
  s.up = {1, 0, 0};  // parallel to right
  Diagnostics diagnostics;
  EXPECT_THROW(convert_camera(s, 160, 120, diagnostics), InputError);
  s.up = {0, 1, 0};
  s.transform = Transform::scale({1, 0, 1});
  EXPECT_THROW(convert_camera(s, 160, 120, diagnostics), InputError);
}

}  // namespace
}  // namespace fb::pov
