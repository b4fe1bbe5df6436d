// Tracked lens distortion against Blender (docs/camera-model.md, "Lens distortion"): per model of
// Blender's motion tracking, distortion_shot.py makes a clip with that solved distortion, Cycles
// renders the undistorted shot and the compositor's Movie Distortion node ("Distort") distorts it,
// as Blender makes CG for a tracked plate; filmback renders the add-on's export with the
// distortion in the camera (no resampling). Every marker's centroid agrees within 0.05 px.
//
// Noise floor: at 256 spp only the emitters' edge pixels are noisy; filmback's centroids move by
// 0.001-0.008 px between seeds. The node's bilinear resampling moves the composite's centroids by
// 0.02-0.03 px from the exact distorted image (measured by applying the node's mapping to
// filmback's undistorted render: docs/camera-model.md, "Lens distortion"), which the 0.05 px
// limit leaves room for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "tests/blender/blender_shot.h"
#include "tests/support/blobs.h"

namespace fb::test {
namespace {

constexpr double kMaxCentroidErrorPx = 0.05;
// A filmback blob is a Cycles blob's when within this; the markers are > 15 px apart.
constexpr double kMatchRadiusPx = 1.0;
// The distortion must move some marker at least this far, or the test shows nothing.
constexpr double kMinShiftPx = 1.5;
// The composite's resampling leaves faint values around the blobs; the markers are > 1.
constexpr double kBlobThreshold = 1e-3;

// One per entry of DISTORTIONS in distortion_shot.py.
const char* const kModels[] = {"polynomial", "division", "nuke", "brown"};

class BlenderDistortion : public WithBlender<testing::TestWithParam<const char*>> {};

TEST_P(BlenderDistortion, MarkersLandWhereTheMovieDistortionNodePutsThem) {
  const std::string name = GetParam();
  const ShotRenders r =
      render_shot(blender, name, std::filesystem::path(FILMBACK_BLENDER_WORK_DIR) / name,
                  FILMBACK_DISTORTION_SHOT_PY);
  ASSERT_EQ(r.filmback.width, r.cycles.width);
  ASSERT_EQ(r.filmback.height, r.cycles.height);
  EXPECT_NE(r.filmback_log.find(" through perspective"), std::string::npos) << r.filmback_log;
  EXPECT_EQ(r.filmback_log.find("warning:"), std::string::npos) << r.filmback_log;

  const std::vector<Blob> cycles = find_blobs(r.cycles, kBlobThreshold);
  const std::vector<Blob> filmback = find_blobs(r.filmback, kBlobThreshold);
  EXPECT_EQ(cycles.size(), r.markers.size()) << "blobs in the distorted Cycles render";
  EXPECT_EQ(filmback.size(), r.markers.size()) << "blobs in the filmback render";
  std::printf("Model %s: Blender (build, export, Cycles, compositor) %.1f s; filmback %.1f s\n",
              name.c_str(), r.blender_s, r.filmback_s);
  std::printf("%-14s %9s %9s %8s %8s %8s %8s\n", "marker", "cycles_x", "cycles_y", "moved_px",
              "dx_px", "dy_px", "|d|_px");
  double worst_px = 0, most_moved_px = 0;
  for (const Record& marker : r.markers) {
    const std::string& id = marker.text("name");
    // The undistorted projection; the distorted blob is the Cycles blob nearest to it.
    const double ux = marker.number("blender_x_px"), uy = marker.number("blender_y_px");
    const Blob* c = nearest_blob(cycles, ux, uy, 10.0);
    if (!c) {
      ADD_FAILURE() << id << ": no Cycles blob within 10 px of (" << ux << ", " << uy << ")";
      continue;
    }
    const Blob* f = nearest_blob(filmback, c->x_px, c->y_px, kMatchRadiusPx);
    if (!f) {
      ADD_FAILURE() << id << ": no filmback blob within " << kMatchRadiusPx
                    << " px of the distorted Cycles blob at (" << c->x_px << ", " << c->y_px << ")";
      continue;
    }
    const double moved = std::hypot(c->x_px - ux, c->y_px - uy);
    const double d = std::hypot(f->x_px - c->x_px, f->y_px - c->y_px);
    worst_px = std::max(worst_px, d);
    most_moved_px = std::max(most_moved_px, moved);
    std::printf("%-14s %9.4f %9.4f %8.3f %+8.4f %+8.4f %8.4f\n", id.c_str(), c->x_px, c->y_px,
                moved, f->x_px - c->x_px, f->y_px - c->y_px, d);
    EXPECT_LT(d, kMaxCentroidErrorPx) << id << ": centroids differ";
  }
  EXPECT_GT(most_moved_px, kMinShiftPx) << "the distortion moves no marker: the test shows nothing";
  std::printf(
      "max centroid difference %.4f px (limit %.2f); the distortion moves markers up to "
      "%.2f px\n",
      worst_px, kMaxCentroidErrorPx, most_moved_px);
}

INSTANTIATE_TEST_SUITE_P(Against, BlenderDistortion, testing::ValuesIn(kModels),
                         [](const testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param);
                         });

}  // namespace
}  // namespace fb::test
