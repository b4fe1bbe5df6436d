// Blender's own deformation against Cycles (deform_shot.py): emissive markers on meshes that
// Blender deforms, exported as Blender's evaluated positions (FILMBACK_deformation) and rendered
// by Cycles and filmback.
//  - A two-bone armature bent at its joint, the same under a Subdivision Surface (Blender's
//    evaluated mesh at render level, whose topology is not the base mesh's), a shape-key blend,
//    and a marker moved by a shape key repeated by an Array modifier: each marker's centroid in
//    filmback's render within 0.1 px of Cycles', and within 0.5 px of Blender's projection of its
//    evaluated centre (off the axis a sphere's image centroid is not its projected centre).
//  - A shape key sliding a marker during the shutter, with the object's Cycles motion steps 1, 3
//    and 7: filmback builds as many motion steps as Cycles stores positions (3, 9, 129); its
//    streak is the travel between Blender's evaluated centres at shutter open and close within
//    0.5 px, and Cycles' streak (over 99.22 % of the shutter, blender_motion_test.cpp) within
//    1 % once shortened to it; the centroids agree within 0.1 px once Cycles' is moved to the
//    whole shutter's.
//  - A bone swinging a marker 90 degrees along an arc with steps 1 and 3: the arc's centroid
//    within 0.1 px of Cycles' (the two counts' centroids lie 1.75 px apart).
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
#include "tests/support/commands.h"

namespace fb::test {
namespace {

constexpr double kMaxDeformCentroidErrorPx = 0.1;
constexpr double kMaxDeformProjectionErrorPx = 0.5;
constexpr double kMaxDeformLengthErrorPx = 0.5;
constexpr double kMaxDeformLengthRatioError = 0.01;
constexpr double kDeformMatchRadiusPx = 3.0;  // markers are > 25 px apart
constexpr double kDeformBlobThreshold = 0.0;  // black world: anything brighter is a marker

ShotRenders render_deform_shot(const std::filesystem::path& blender, const std::string& shot) {
  return render_shot(blender, shot, std::filesystem::path(FILMBACK_BLENDER_WORK_DIR) / shot,
                     FILMBACK_DEFORM_SHOT_PY);
}

class BlenderDeformStill : public WithBlender<testing::TestWithParam<const char*>> {};

TEST_P(BlenderDeformStill, MarkersOnTheDeformedMeshMatchCycles) {
  const ShotRenders r = render_deform_shot(blender, GetParam());
  const std::vector<Blob> cycles_blobs = find_blobs(r.cycles, kDeformBlobThreshold);
  const std::vector<Blob> filmback_blobs = find_blobs(r.filmback, kDeformBlobThreshold);
  ASSERT_EQ(cycles_blobs.size(), r.markers.size()) << "blobs in the Cycles render";
  ASSERT_EQ(filmback_blobs.size(), r.markers.size()) << "blobs in the filmback render";
  std::printf("Blender deformation '%s', %sx%s at %s spp; Blender %.1f s, filmback %.1f s\n",
              GetParam(), r.shot.text("width_px").c_str(), r.shot.text("height_px").c_str(),
              r.shot.text("samples").c_str(), r.blender_s, r.filmback_s);
  std::printf("%-10s | %9s %9s | %9s %9s | %9s %9s | %8s\n", "marker", "blender_x", "blender_y",
              "fb_x", "fb_y", "cycles_x", "cycles_y", "fb-cy");
  for (const Record& m : r.markers) {
    const std::string name = m.text("name");
    const double x = m.number("x_px"), y = m.number("y_px");
    const Blob* fb = nearest_blob(filmback_blobs, x, y, kDeformMatchRadiusPx);
    const Blob* cy = nearest_blob(cycles_blobs, x, y, kDeformMatchRadiusPx);
    ASSERT_NE(fb, nullptr) << name << ": no filmback blob near (" << x << ", " << y << ")";
    ASSERT_NE(cy, nullptr) << name << ": no Cycles blob near (" << x << ", " << y << ")";
    const double apart = std::hypot(fb->x_px - cy->x_px, fb->y_px - cy->y_px);
    std::printf("%-10s | %9.4f %9.4f | %9.4f %9.4f | %9.4f %9.4f | %8.4f\n", name.c_str(), x, y,
                fb->x_px, fb->y_px, cy->x_px, cy->y_px, apart);
    EXPECT_LT(apart, kMaxDeformCentroidErrorPx) << name << ": filmback's centroid against Cycles'";
    EXPECT_LT(std::hypot(fb->x_px - x, fb->y_px - y), kMaxDeformProjectionErrorPx)
        << name << ": filmback's centroid against Blender's evaluated centre";
  }
}

std::string deform_shot_name(const testing::TestParamInfo<const char*>& info) {
  return info.param;
}

INSTANTIATE_TEST_SUITE_P(Shots, BlenderDeformStill,
                         testing::Values("armature", "shapekey", "subdivided", "array"),
                         deform_shot_name);

class BlenderDeformBlur : public WithBlender<testing::TestWithParam<const char*>> {};

TEST_P(BlenderDeformBlur, StreaksOfEvaluatedShapesMatchCycles) {
  const ShotRenders r = render_deform_shot(blender, GetParam());
  const std::string steps = "1 moving instance (up to " + r.shot.text("positions") + " motion";
  EXPECT_NE(r.filmback_log.find(steps), std::string::npos) << r.filmback_log;
  // `filmback info` says which path the shot took: Blender's shapes, not the glTF morph targets.
  const std::filesystem::path work = std::filesystem::path(FILMBACK_BLENDER_WORK_DIR) / GetParam();
  run_logged(quoted(FILMBACK_EXE) + " info " + quoted(work / "shot.gltf"), work / "info.txt");
  const std::string info = read_text(work / "info.txt");
  EXPECT_NE(info.find("evaluated shapes at " + r.shot.text("positions") + " times"),
            std::string::npos)
      << info;
  const std::vector<Blob> cycles_blobs = find_blobs(r.cycles, kDeformBlobThreshold);
  const std::vector<Blob> filmback_blobs = find_blobs(r.filmback, kDeformBlobThreshold);
  ASSERT_EQ(cycles_blobs.size(), r.markers.size()) << "blobs in the Cycles render";
  ASSERT_EQ(filmback_blobs.size(), r.markers.size()) << "blobs in the filmback render";
  const double c = r.shot.number("cycles_shutter_fraction");
  std::printf(
      "Blender deformation blur '%s' (%s positions), %sx%s at %s spp; Blender %.1f s, "
      "filmback %.1f s\n",
      GetParam(), r.shot.text("positions").c_str(), r.shot.text("width_px").c_str(),
      r.shot.text("height_px").c_str(), r.shot.text("samples").c_str(), r.blender_s, r.filmback_s);
  std::printf("%-8s %8s | %9s %9s %8s | %9s %9s %8s | %8s\n", "marker", "travel", "fb_x", "fb_y",
              "fb_L", "cycles_x", "cycles_y", "cycles_L", "fb-cy");
  for (const Record& m : r.markers) {
    const std::string name = m.text("name");
    const double x0 = m.number("open_x_px"), y0 = m.number("open_y_px");
    const double dx = m.number("close_x_px") - x0, dy = m.number("close_y_px") - y0;
    const double travel = std::hypot(dx, dy);
    const double ux = travel > 0 ? dx / travel : 1, uy = travel > 0 ? dy / travel : 0;
    const double mid_x = x0 + dx / 2, mid_y = y0 + dy / 2;
    const Blob* fb = nearest_blob(filmback_blobs, mid_x, mid_y, kDeformMatchRadiusPx);
    // Cycles' streak stops short by (1 - c) of the travel: its centroid by half that.
    const double cycles_x = mid_x - (1 - c) * dx / 2, cycles_y = mid_y - (1 - c) * dy / 2;
    const Blob* cy = nearest_blob(cycles_blobs, cycles_x, cycles_y, kDeformMatchRadiusPx);
    ASSERT_NE(fb, nullptr) << name << ": no filmback blob near (" << mid_x << ", " << mid_y << ")";
    ASSERT_NE(cy, nullptr) << name << ": no Cycles blob near (" << cycles_x << ", " << cycles_y
                           << ")";
    const double fb_length = streak_length_px(*fb, ux, uy);
    const double cy_length = streak_length_px(*cy, ux, uy);
    const double apart = std::hypot(fb->x_px - (cy->x_px + (1 - c) * dx / 2),
                                    fb->y_px - (cy->y_px + (1 - c) * dy / 2));
    std::printf("%-8s %8.3f | %9.4f %9.4f %8.3f | %9.4f %9.4f %8.3f | %8.4f\n", name.c_str(),
                travel, fb->x_px, fb->y_px, fb_length, cy->x_px, cy->y_px, cy_length, apart);
    EXPECT_LT(apart, kMaxDeformCentroidErrorPx)
        << name << ": filmback's centroid against Cycles', moved to the whole shutter";
    if (travel > 0) {
      EXPECT_NEAR(fb_length, travel, kMaxDeformLengthErrorPx) << name << ": filmback's streak";
      EXPECT_NEAR(fb_length * c / cy_length, 1.0, kMaxDeformLengthRatioError)
          << name << ": filmback's streak, shortened to Cycles' shutter, against Cycles'";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Steps, BlenderDeformBlur, testing::Values("blur1", "blur3", "blur7"),
                         deform_shot_name);

// An arc: a marker on a bone turning 90 degrees about the view axis during the shutter. Both
// renderers interpolate linearly between their motion positions, so the streak is the same
// chords in both only if filmback builds Cycles' count: the 3- and 9-position centroids lie
// 1.75 px apart. Cycles' streak stops at 99.22 % of the shutter; the missing tail sits at the
// close position, so the whole shutter's centroid is c C_cycles + (1 - c) P_close (within
// 0.002 px for this arc).
class BlenderDeformSwing : public WithBlender<testing::TestWithParam<const char*>> {};

TEST_P(BlenderDeformSwing, ArcsCutIntoCyclesChordsMatchCycles) {
  const ShotRenders r = render_deform_shot(blender, GetParam());
  const std::string steps = "1 moving instance (up to " + r.shot.text("positions") + " motion";
  EXPECT_NE(r.filmback_log.find(steps), std::string::npos) << r.filmback_log;
  const std::vector<Blob> cycles_blobs = find_blobs(r.cycles, kDeformBlobThreshold);
  const std::vector<Blob> filmback_blobs = find_blobs(r.filmback, kDeformBlobThreshold);
  ASSERT_EQ(cycles_blobs.size(), 1u) << "blobs in the Cycles render";
  ASSERT_EQ(filmback_blobs.size(), 1u) << "blobs in the filmback render";
  ASSERT_EQ(r.markers.size(), 1u);
  const Record& m = r.markers[0];
  const double c = r.shot.number("cycles_shutter_fraction");
  const Blob &fb = filmback_blobs[0], &cy = cycles_blobs[0];
  const double whole_x = c * cy.x_px + (1 - c) * m.number("close_x_px");
  const double whole_y = c * cy.y_px + (1 - c) * m.number("close_y_px");
  const double apart = std::hypot(fb.x_px - whole_x, fb.y_px - whole_y);
  std::printf(
      "Blender deformation swing '%s' (%s positions): open (%.3f, %.3f), close (%.3f, "
      "%.3f); filmback (%.4f, %.4f), Cycles over the whole shutter (%.4f, %.4f): %.4f px; "
      "Blender %.1f s, filmback %.1f s\n",
      GetParam(), r.shot.text("positions").c_str(), m.number("open_x_px"), m.number("open_y_px"),
      m.number("close_x_px"), m.number("close_y_px"), fb.x_px, fb.y_px, whole_x, whole_y, apart,
      r.blender_s, r.filmback_s);
  EXPECT_LT(apart, kMaxDeformCentroidErrorPx)
      << "filmback's arc centroid against Cycles', moved to the whole shutter";
}

INSTANTIATE_TEST_SUITE_P(Steps, BlenderDeformSwing, testing::Values("swing1", "swing3"),
                         deform_shot_name);

}  // namespace
}  // namespace fb::test
