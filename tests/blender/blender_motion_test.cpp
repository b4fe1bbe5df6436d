// Motion blur against Blender (motion_shot.py): markers moving at constant speed during a box
// shutter, exported with their animation by Blender's glTF exporter, rendered by Cycles with
// motion blur and by filmback. A sphere of image diameter d moving by L draws the disk convolved
// with a segment, so its second moments along and across the travel differ by exactly L^2 / 12
// (moments add under convolution; the disk and the 1 px box add the same to both), and its
// centroid is the time average of the sphere's image centre weighted by the image's area, which
// motion_shot.py integrates from Blender's own projection. For each marker:
//  - filmback's centroid agrees with that analytic one within 0.1 px, and its streak length with
//    the distance between Blender's projections at shutter open and close within 0.5 px;
//  - Cycles 3.4 exposes only the first 99.22 % of the shutter (notes/blender-camera.md, pitfall
//    10): its streak is that much shorter and its centroid is the analytic one over that part.
//    Allowing for that, the two renderers agree within 0.1 px and 1 % in length.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tests/blender/blender_shot.h"
#include "tests/support/blobs.h"

namespace fb::test {
namespace {

constexpr double kMaxCentroidErrorPx = 0.1;
constexpr double kMaxLengthErrorPx = 0.5;
constexpr double kMaxLengthRatioError = 0.01;
constexpr double kMatchRadiusPx = 2.0;  // markers are > 40 px apart
constexpr double kBlobThreshold = 0.0;  // black world: anything brighter is a marker

struct Streak {
  double x_px, y_px;  // centroid
  double length_px;   // sqrt(12 (along - across)), 0 for a still marker
};

// The blob's centroid, and its travel from the second moments along `ux, uy` (unit) and across.
Streak measure(const Blob& blob, double ux, double uy) {
  return {blob.x_px, blob.y_px, streak_length_px(blob, ux, uy)};
}

using BlenderMotion = WithBlender<>;

TEST_F(BlenderMotion, StreaksMatchTheAnalyticTravelAndCycles) {
  const ShotRenders r =
      render_shot(blender, "motion", std::filesystem::path(FILMBACK_BLENDER_WORK_DIR) / "motion");
  ASSERT_NE(r.filmback_log.find("time samples for 2 moving instances"), std::string::npos)
      << r.filmback_log;
  const std::vector<Blob> cycles_blobs = find_blobs(r.cycles, kBlobThreshold);
  const std::vector<Blob> filmback_blobs = find_blobs(r.filmback, kBlobThreshold);
  ASSERT_EQ(cycles_blobs.size(), r.markers.size()) << "blobs in the Cycles render";
  ASSERT_EQ(filmback_blobs.size(), r.markers.size()) << "blobs in the filmback render";

  std::printf(
      "Blender motion blur, %sx%s at %s spp, shutter %s to %s s; Blender %.1f s, filmback "
      "%.1f s\n",
      r.shot.text("width_px").c_str(), r.shot.text("height_px").c_str(),
      r.shot.text("samples").c_str(), r.shot.text("shutter_open_s").c_str(),
      r.shot.text("shutter_close_s").c_str(), r.blender_s, r.filmback_s);
  std::printf("%-8s %8s | %9s %9s %8s | %9s %9s %8s | %9s %9s %8s\n", "marker", "travel", "exact_x",
              "exact_y", "exact_L", "fb_x", "fb_y", "fb_L", "cycles_x", "cycles_y", "cycles_L");
  for (const Record& m : r.markers) {
    const double x0 = m.number("open_x_px"), y0 = m.number("open_y_px");
    const double dx = m.number("close_x_px") - x0, dy = m.number("close_y_px") - y0;
    const double travel = std::hypot(dx, dy);
    const double ux = travel > 0 ? dx / travel : 1, uy = travel > 0 ? dy / travel : 0;
    const double exact_x = m.number("centroid_x_px"), exact_y = m.number("centroid_y_px");
    const double cycles_x = m.number("cycles_centroid_x_px");
    const double cycles_y = m.number("cycles_centroid_y_px");
    const double c = r.shot.number("cycles_shutter_fraction");
    const Blob* fb = nearest_blob(filmback_blobs, exact_x, exact_y, kMatchRadiusPx);
    const Blob* cy = nearest_blob(cycles_blobs, cycles_x, cycles_y, kMatchRadiusPx);
    const std::string name = m.text("name");
    ASSERT_NE(fb, nullptr) << name << ": no filmback blob near (" << exact_x << ", " << exact_y
                           << ")";
    ASSERT_NE(cy, nullptr) << name << ": no Cycles blob near (" << cycles_x << ", " << cycles_y
                           << ")";
    const Streak f = measure(*fb, ux, uy), k = measure(*cy, ux, uy);
    std::printf("%-8s %8.3f | %9.4f %9.4f %8.3f | %9.4f %9.4f %8.3f | %9.4f %9.4f %8.3f\n",
                name.c_str(), travel, exact_x, exact_y, travel, f.x_px, f.y_px, f.length_px, k.x_px,
                k.y_px, k.length_px);
    EXPECT_LT(std::hypot(f.x_px - exact_x, f.y_px - exact_y), kMaxCentroidErrorPx)
        << name << ": filmback's centroid against the analytic one";
    EXPECT_LT(std::hypot(k.x_px - cycles_x, k.y_px - cycles_y), kMaxCentroidErrorPx)
        << name << ": Cycles' centroid against the analytic one for its 99.22 % shutter";
    if (travel > 0) {
      EXPECT_NEAR(f.length_px, travel, kMaxLengthErrorPx) << name << ": filmback's streak";
      EXPECT_NEAR(f.length_px * c / k.length_px, 1.0, kMaxLengthRatioError)
          << name << ": filmback's streak, shortened to 99.22 %, against Cycles'";
    }
  }
}

}  // namespace
}  // namespace fb::test
