// Rolling shutter and animated lenses against Cycles 3.4 (lens_motion_shot.py): emissive markers
// rendered by Cycles and by filmback from the add-on's export (docs/camera-model.md, "Rolling
// shutter" and "Animated lenses").
//  - rolling: markers moving 16-30 px over the shutter under Cycles' rolling shutter (duration
//    0.1). Each marker's centroid in filmback's render within 0.1 px of Cycles'; and Cycles' own
//    centroid within 0.5 px of where a top-first scan puts it (the rows' times solved for the
//    marker's image, the motion-blur share averaging out), so that the direction is Cycles'
//    render's, not only its source's.
//  - lens: a zoom over the open shutter (radial streaks of up to 4 px), a rack focus, an f-stop
//    and a lens shift keyed over frames, rendered at a frame the file's scalar values are not
//    for. Each marker's centroid and its blur's size (the RMS radius sqrt(<dx^2 + dy^2>), which
//    grows with the circle of confusion and the zoom's streak) within 0.1 px of Cycles'.
#include <gtest/gtest.h>

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
constexpr double kMaxRadiusErrorPx = 0.1;
constexpr double kMaxScanPredictionErrorPx = 0.5;
constexpr double kMatchRadiusPx = 3.0;  // markers are > 15 px apart
constexpr double kBlobThreshold = 0.0;  // black world: anything brighter is a marker

double rms_radius_px(const Blob& blob) {
  const Spread s = spread(blob);
  return std::sqrt(s.xx + s.yy);
}

ShotRenders render(const std::filesystem::path& blender, const std::string& shot) {
  return render_shot(blender, shot,
                     std::filesystem::path(FILMBACK_BLENDER_WORK_DIR) / ("lens_motion_" + shot));
}

using BlenderLensMotion = WithBlender<>;

// Where a top-first scan images a marker at (x0, y0) at the frame's time moving by (vx, vy) over
// the shutter: its rows' shutter fraction s = 1/2 + (1 - d) ((y + 1/2) / H - 1/2) (the pixel row
// of a centre y is floor(y), read at (row + 1) / H) at the position it has then, solved by
// iteration (|vy| (1 - d) / H < 1 contracts).
std::pair<double, double> scanned_at(double x0, double y0, double vx, double vy, double d,
                                     double height, bool top_first) {
  double y = y0, s = 0.5;
  for (int i = 0; i < 50; ++i) {
    const double r = (y + 0.5) / height;
    s = 0.5 + (1 - d) * ((top_first ? r : 1 - r) - 0.5);
    y = y0 + vy * (s - 0.5);
  }
  return {x0 + vx * (s - 0.5), y};
}

TEST_F(BlenderLensMotion, RollingShutterMatchesCycles) {
  const ShotRenders r = render(blender, "rolling");
  ASSERT_NE(r.filmback_log.find("rolling top to bottom, each row 0.1 of it"), std::string::npos)
      << r.filmback_log;
  const std::vector<Blob> cycles = find_blobs(r.cycles, kBlobThreshold);
  const std::vector<Blob> filmback = find_blobs(r.filmback, kBlobThreshold);
  ASSERT_EQ(cycles.size(), r.markers.size()) << "blobs in the Cycles render";
  ASSERT_EQ(filmback.size(), r.markers.size()) << "blobs in the filmback render";
  const double d = r.shot.number("rolling_duration"), height = r.shot.number("height_px");
  std::printf("Rolling shutter (duration %g), %sx%s at %s spp; Blender %.1f s, filmback %.1f s\n",
              d, r.shot.text("width_px").c_str(), r.shot.text("height_px").c_str(),
              r.shot.text("samples").c_str(), r.blender_s, r.filmback_s);
  std::printf("%-12s | %8s %8s | %8s %8s | %8s %8s | %8s %8s | %7s\n", "marker", "frame_x",
              "frame_y", "top_x", "top_y", "bottom_x", "bottom_y", "cycles_x", "cycles_y", "fb-cy");
  for (const Record& m : r.markers) {
    const double x0 = m.number("frame_x_px"), y0 = m.number("frame_y_px");
    const double vx = m.number("travel_x_px"), vy = m.number("travel_y_px");
    const auto [tx, ty] = scanned_at(x0, y0, vx, vy, d, height, true);
    const auto [bx, by] = scanned_at(x0, y0, vx, vy, d, height, false);
    const std::string name = m.text("name");
    const Blob* cy = nearest_blob(cycles, tx, ty, kMatchRadiusPx);
    ASSERT_NE(cy, nullptr) << name << ": no Cycles blob near the top-first scan's (" << tx << ", "
                           << ty << ")";
    const Blob* fb = nearest_blob(filmback, cy->x_px, cy->y_px, kMatchRadiusPx);
    ASSERT_NE(fb, nullptr) << name << ": no filmback blob near Cycles'";
    const double error = std::hypot(fb->x_px - cy->x_px, fb->y_px - cy->y_px);
    std::printf("%-12s | %8.3f %8.3f | %8.3f %8.3f | %8.3f %8.3f | %8.3f %8.3f | %7.4f\n",
                name.c_str(), x0, y0, tx, ty, bx, by, cy->x_px, cy->y_px, error);
    EXPECT_LT(std::hypot(cy->x_px - tx, cy->y_px - ty), kMaxScanPredictionErrorPx)
        << name << ": Cycles' marker against a top-first scan";
    EXPECT_LT(error, kMaxCentroidErrorPx) << name << ": filmback's centroid against Cycles'";
  }
}

TEST_F(BlenderLensMotion, ZoomRackFocusAndShiftMatchCycles) {
  const ShotRenders r = render(blender, "lens");
  ASSERT_NE(r.filmback_log.find("the zoom"), std::string::npos) << r.filmback_log;
  const std::vector<Blob> cycles = find_blobs(r.cycles, kBlobThreshold);
  const std::vector<Blob> filmback = find_blobs(r.filmback, kBlobThreshold);
  ASSERT_EQ(cycles.size(), r.markers.size()) << "blobs in the Cycles render";
  ASSERT_EQ(filmback.size(), r.markers.size()) << "blobs in the filmback render";
  std::printf("Animated lens, %sx%s at %s spp; Blender %.1f s, filmback %.1f s\n",
              r.shot.text("width_px").c_str(), r.shot.text("height_px").c_str(),
              r.shot.text("samples").c_str(), r.blender_s, r.filmback_s);
  std::printf("%-10s | %8s %8s | %8s %8s %8s | %8s %8s %8s | %7s %7s\n", "marker", "frame_x",
              "frame_y", "cycles_x", "cycles_y", "cy_rms", "fb_x", "fb_y", "fb_rms", "d_xy",
              "d_rms");
  for (const Record& m : r.markers) {
    const double x0 = m.number("frame_x_px"), y0 = m.number("frame_y_px");
    const std::string name = m.text("name");
    const Blob* cy = nearest_blob(cycles, x0, y0, kMatchRadiusPx);
    ASSERT_NE(cy, nullptr) << name << ": no Cycles blob near (" << x0 << ", " << y0 << ")";
    const Blob* fb = nearest_blob(filmback, cy->x_px, cy->y_px, kMatchRadiusPx);
    ASSERT_NE(fb, nullptr) << name << ": no filmback blob near Cycles'";
    const double error = std::hypot(fb->x_px - cy->x_px, fb->y_px - cy->y_px);
    const double cy_rms = rms_radius_px(*cy), fb_rms = rms_radius_px(*fb);
    std::printf("%-10s | %8.3f %8.3f | %8.3f %8.3f %8.3f | %8.3f %8.3f %8.3f | %7.4f %7.4f\n",
                name.c_str(), x0, y0, cy->x_px, cy->y_px, cy_rms, fb->x_px, fb->y_px, fb_rms, error,
                fb_rms - cy_rms);
    EXPECT_LT(error, kMaxCentroidErrorPx) << name << ": filmback's centroid against Cycles'";
    EXPECT_NEAR(fb_rms, cy_rms, kMaxRadiusErrorPx) << name << ": the blur's RMS radius";
  }
}

}  // namespace
}  // namespace fb::test
