// Extreme apertures and focus distances (scenes/hard/README.md, "apertures and focus"): f/0.95,
// f/182 (a pinhole photograph's aperture) focused at infinity, and focus approaching the focal
// length blur each marker into the thin lens's circle of confusion; focus at or inside the focal
// length, where a lens forms no real image, is refused before anything renders.
#include <gtest/gtest.h>

#include <cmath>

#include "core/util/error.h"
#include "hard_case.h"
#include "support/blobs.h"
#include "support/defocus.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::load_hard_scene;
using test::report_case;

// The blob nearest to a raster point.
const test::Blob& nearest(const std::vector<test::Blob>& blobs, Vec2d at) {
  const test::Blob* best = &blobs.at(0);
  for (const test::Blob& b : blobs)
    if (std::hypot(b.x_px - at.x, b.y_px - at.y) < std::hypot(best->x_px - at.x, best->y_px - at.y))
      best = &b;
  return *best;
}

// Renders the file's emissive markers through its thin lens and through a pinhole, and checks
// each marker's blur against the circle of confusion: the thin-lens image is the pinhole image
// convolved with the blur disk, and second moments of convolved images add, so the disk's
// diameter is 4 sqrt(<x^2>_lens - <x^2>_pinhole) (a disk of diameter d has <x^2> = d^2 / 16).
// Errors are relative where the circle spans more than a pixel, else in pixels.
void check_blur(const char* file, RenderOptions options, double relative_limit) {
  const Scene scene = load_hard_scene(file);
  SceneCamera camera = scene.cameras.at(0);
  options.camera_overrides.apply(camera);
  const PhysicalCamera& lens = camera.physical;
  const uint32_t width = *scene.settings.width_px, height = *scene.settings.height_px;
  const double pixel_mm = lens.sensor_width_mm / width;  // fit AUTO on a landscape frame
  options.samples_per_pixel = 1024;
  options.filter = "box";
  options.integrator = "path:max_depth=0";
  const test::TimedRender r = test::render_timed(scene, options);
  options.camera_overrides.fstop = HUGE_VAL;
  const test::TimedRender pinhole = test::render_timed(scene, options);
  const std::vector<test::Blob> blobs = test::find_blobs(r.result.image, 0),
                                sharp = test::find_blobs(pinhole.result.image, 0);
  ASSERT_EQ(blobs.size(), scene.instances.size()) << file;
  const Transform camera_from_world = camera.world_from_camera.inverse();
  double worst_relative = 0, worst_sharp_px = 0, worst_centre_px = 0;
  for (const MeshInstance& instance : scene.instances) {
    const Vec3d centre = instance.world_from_object.translation();
    const double depth = -camera_from_world.point(centre).z;
    const Vec2d at = test::project(camera, width, height, centre);
    const test::Blob& blob = nearest(blobs, at);
    // The blur is centred on the chief ray: the pinhole projection of the marker's centre.
    worst_centre_px = std::max(worst_centre_px, std::hypot(blob.x_px - at.x, blob.y_px - at.y));
    const test::Spread s = test::spread(blob), s0 = test::spread(nearest(sharp, at));
    const double expected = test::circle_of_confusion_mm(lens.focal_length_mm, lens.fstop,
                                                         lens.focus_distance_m, depth) /
                            pixel_mm;
    // The disk is round: its diameter from the mean of the two axes' excess moments.
    const double blur = 4 * std::sqrt(std::max(0.0, (s.xx - s0.xx + s.yy - s0.yy) / 2));
    if (expected > 1)
      worst_relative = std::max(worst_relative, std::abs(blur / expected - 1));
    else
      worst_sharp_px = std::max(worst_sharp_px, std::abs(blur - expected));
  }
  const uint64_t non_finite = r.result.stats.dropped_samples + pinhole.result.stats.dropped_samples;
  const double seconds = r.seconds + pinhole.seconds;
  report_case(std::string(file) + " blur", non_finite, worst_relative, relative_limit,
              "worst |blur diameter / circle of confusion - 1|", seconds);
  report_case(std::string(file) + " sharp", non_finite, worst_sharp_px, 0.25,
              "worst |blur - c| where c < 1 px, px", seconds);
  report_case(std::string(file) + " centres", non_finite, worst_centre_px, 0.05,
              "worst |blur centroid - pinhole projection|, px", seconds);
}

TEST(Aperture, F095BlursAsTheCircleOfConfusion) {
  check_blur("aperture_f0_95.gltf", {}, 0.02);
}

TEST(Aperture, F182FocusedAtInfinityBlursAsTheCircleOfConfusion) {
  check_blur("aperture_f182.gltf", {}, 0.02);
}

// Blender's thin lens keeps the image distance at f, so nothing diverges as the focus distance
// D_f approaches f (a real lens's image distance f D_f / (D_f - f) grows without bound: 5.05 m at
// 1.01 f, 50 m at 1.001 f): the blur still follows c = A f |1/D - 1/D_f|.
TEST(Aperture, FocusApproachingTheFocalLengthBlursAsTheCircleOfConfusion) {
  check_blur("focus_near_focal_length.gltf", {}, 0.02);
  RenderOptions closer;
  closer.camera_overrides.focus_distance_m = 0.05 * (1 + 1e-6);
  check_blur("focus_near_focal_length.gltf", closer, 0.02);
}

TEST(Aperture, FocusAtOrInsideTheFocalLengthIsRefused) {
  const Scene scene = load_hard_scene("focus_inside_focal_length.gltf");
  RenderOptions options;
  options.show_progress = false;
  try {
    RenderJob(scene, options, test::loader());
    FAIL() << "a focus distance of 0.04 m with a 50 mm lens rendered";
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const char* part : {"focus_inside_focal_length.gltf", "cameras[0]", "0.04 m", "50 mm",
                             "expected a focus distance over 0.05 m"})
      EXPECT_NE(message.find(part), std::string::npos) << part << " in: " << message;
  }
  // Typed on the command line, the same value is a usage error naming the option.
  options.camera_overrides.focus_distance_m = 0.05;
  const Scene near = load_hard_scene("focus_near_focal_length.gltf");
  try {
    RenderJob(near, options, test::loader());
    FAIL() << "a focus distance equal to the focal length rendered";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--focus-distance"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fb
