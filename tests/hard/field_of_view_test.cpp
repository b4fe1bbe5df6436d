// A 2000 mm telephoto (0.5 degrees across) and an 8 mm ultra-wide (160 degrees across) put every
// marker where the pinhole formula puts it (scenes/hard/README.md, "fields of view"). The
// markers are emissive squares on a plane perpendicular to the view axis, whose images are exact
// squares, so their centroids are the projections of their centres.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "hard_case.h"
#include "support/blobs.h"

namespace fb {
namespace {

using test::load_hard_scene;
using test::report_case;

// Where a camera-space point lands for a pinhole of horizontal field of view alpha =
// 2 atan(w / 2f) (sensor width w, fit AUTO on a landscape frame): x = W/2 (1 + X / (-Z) /
// tan(alpha/2)), and the vertical half-extent is tan(alpha/2) H / W.
Vec2d pinhole_raster(Vec3d p, double tan_half_x, uint32_t width, uint32_t height) {
  const double tan_half_y = tan_half_x * height / width;
  return {width / 2.0 * (1 + p.x / -p.z / tan_half_x),
          height / 2.0 * (1 - p.y / -p.z / tan_half_y)};
}

void check_markers(const char* file, double expected_fov_deg) {
  const Scene scene = load_hard_scene(file);
  const SceneCamera& camera = scene.cameras.at(0);
  const uint32_t width = *scene.settings.width_px, height = *scene.settings.height_px;
  const double tan_half_x = camera.physical.sensor_width_mm / (2 * camera.physical.focal_length_mm);
  const double fov_deg = 2 * std::atan(tan_half_x) * 180 / std::numbers::pi;
  EXPECT_NEAR(fov_deg, expected_fov_deg, 0.01) << file;
  const test::TimedRender r = test::render_timed(scene, test::box_filtered(64, "path:max_depth=0"));
  const std::vector<test::Blob> blobs = test::find_blobs(r.result.image, 1e-3);
  const Transform camera_from_world = camera.world_from_camera.inverse();
  double worst = 0;
  size_t markers = 0;
  for (const MeshInstance& instance : scene.instances) {
    ++markers;
    const Vec2d expected =
        pinhole_raster(camera_from_world.point(instance.world_from_object.translation()),
                       tan_half_x, width, height);
    double nearest = HUGE_VAL;
    for (const test::Blob& blob : blobs)
      nearest = std::min(nearest, std::hypot(blob.x_px - expected.x, blob.y_px - expected.y));
    worst = std::max(worst, nearest);
  }
  EXPECT_EQ(blobs.size(), markers) << file;
  report_case(std::string(file) + " (" + std::to_string(fov_deg) + " deg)",
              r.result.stats.dropped_samples, worst, 0.02,
              "worst |marker centroid - pinhole projection|, px", r.seconds);
}

TEST(FieldOfView, TelephotoOfHalfADegreeProjectsAsThePinholeFormula) {
  check_markers("fov_2000mm.gltf", 0.4999);
}

TEST(FieldOfView, UltraWideOf160DegreesProjectsAsThePinholeFormula) {
  check_markers("fov_8mm.gltf", 160.0);
}

}  // namespace
}  // namespace fb
