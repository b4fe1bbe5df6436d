// The tests against Blender itself, one per shot of make_shot.py's table: Debian's Blender builds
// the shot (emissive spheres, "markers", on a black world, seen through the shot's lens, sensor
// fit, frame, shift and aperture), exports it through filmback's add-on and renders it with
// Cycles; filmback renders the export with the same 1 px box filter and sample count
// (blender_shot.h). For each marker:
//  - the image centroids agree within 0.1 px and the fluxes (sums of pixel values) within 2 %;
//  - the blob's disk diameters along x and y (blobs.h; for a defocused marker, the circle of
//    confusion with the sphere's own image) agree within 3 %, and each renderer's agree within 3 %
//    with the analytic value make_shot.py derives from Blender's camera;
//  - a polygonal bokeh's orientation agrees within 2 degrees, and with Cycles' polygon convention.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "tests/blender/blender_shot.h"
#include "tests/support/blobs.h"

namespace fb::test {
namespace {

constexpr double kMaxCentroidErrorPx = 0.1;
constexpr double kMaxFluxError = 0.02;
constexpr double kMaxDiameterError = 0.03;
constexpr double kMaxAngleErrorRad = 2 * std::numbers::pi / 180;
// A blob belongs to a marker when its centroid is this close to the centre of the marker's
// analytic image; markers are > 20 px apart.
constexpr double kMatchRadiusPx = 1.0;
// Background pixels are exactly 0 (black world, emission only); anything brighter is a marker.
constexpr double kBlobThreshold = 0.0;

// One per entry of SHOTS in make_shot.py.
const char* const kShots[] = {
    "default_50mm",     "landscape_auto", "vertical_fit",
    "portrait_auto",    "lens_shift",     "portrait_vertical_shift",
    "wide_12mm",        "tele_600mm",     "far_from_origin",
    "orthographic",     "dof_f1_4",       "bokeh_hexagon",
    "bokeh_anamorphic",
};

// Angles of an n-fold symmetric shape are equal modulo 2 pi / n.
double angle_difference(double a, double b, unsigned n) {
  return std::remainder(a - b, 2 * std::numbers::pi / n);
}

struct Measured {
  double dx_px, dy_px;  // disk diameters along x and y
  double angle_rad;     // NaN unless measured
};

Measured measure(const Blob& blob, unsigned blades, bool polygonal) {
  const Spread s = spread(blob);
  return {disk_diameter_px(s.xx), disk_diameter_px(s.yy),
          polygonal ? orientation_rad(blob, blades) : NAN};
}

double deg(double rad) {
  return rad * 180 / std::numbers::pi;
}

class BlenderShot : public WithBlender<testing::TestWithParam<const char*>> {};

TEST_P(BlenderShot, MarkersMatchCycles) {
  const std::string name = GetParam();
  const ShotRenders r =
      render_shot(blender, name, std::filesystem::path(FILMBACK_BLENDER_WORK_DIR) / name);

  const auto width = uint32_t(r.shot.number("width_px")),
             height = uint32_t(r.shot.number("height_px"));
  ASSERT_EQ(r.cycles.width, width);
  ASSERT_EQ(r.cycles.height, height);
  ASSERT_EQ(r.filmback.width, width) << "filmback did not take the resolution from the file";
  ASSERT_EQ(r.filmback.height, height);
  const std::string model = r.shot.text("camera_model");
  EXPECT_NE(r.filmback_log.find(" through " + model + " "), std::string::npos)
      << "filmback should choose the " << model << " camera; its log:\n"
      << r.filmback_log;
  EXPECT_EQ(r.filmback_log.find("warning:"), std::string::npos)
      << "Blender's export should import without warnings; filmback's log:\n"
      << r.filmback_log;

  ASSERT_FALSE(r.markers.empty());
  const std::vector<Blob> cycles_blobs = find_blobs(r.cycles, kBlobThreshold);
  const std::vector<Blob> filmback_blobs = find_blobs(r.filmback, kBlobThreshold);
  EXPECT_EQ(cycles_blobs.size(), r.markers.size()) << "blobs in the Cycles render";
  EXPECT_EQ(filmback_blobs.size(), r.markers.size()) << "blobs in the filmback render";
  const auto blades = unsigned(r.shot.number("aperture_blades"));

  std::printf(
      "Shot %s: %ux%u at %s spp, 1 px box; Blender (build, export, Cycles) %.1f s, of which "
      "Cycles %.1f s; filmback %.1f s\n",
      name.c_str(), width, height, r.shot.text("samples").c_str(), r.blender_s, r.cycles_s,
      r.filmback_s);
  std::printf("%-20s %9s %9s %8s %8s %8s %7s | %7s %7s %7s %7s %7s %7s", "marker", "cycles_x",
              "cycles_y", "dx_px", "dy_px", "|d|_px", "flux", "dia_x", "fb/cy", "/math", "dia_y",
              "fb/cy", "/math");
  std::printf(blades ? " | %6s %6s %6s\n" : "\n", "angle", "fb-cy", "cy-mat");
  double worst_px = 0, worst_flux = 0, worst_dia = 0, worst_math = 0;
  for (const Record& marker : r.markers) {
    const std::string& id = marker.text("name");
    const double x = marker.number("image_x_px"), y = marker.number("image_y_px");
    const Blob* c = nearest_blob(cycles_blobs, x, y, kMatchRadiusPx);
    const Blob* f = nearest_blob(filmback_blobs, x, y, kMatchRadiusPx);
    if (!c || !f) {
      ADD_FAILURE() << id << ": no " << (c ? "filmback" : "Cycles") << " blob within "
                    << kMatchRadiusPx << " px of the marker's image centre (" << x << ", " << y
                    << ")";
      continue;
    }
    const double expected_angle = marker.number("vertex_angle_rad");
    const bool polygonal = !std::isnan(expected_angle);
    const Measured mc = measure(*c, blades, polygonal), mf = measure(*f, blades, polygonal);
    const double math_x = marker.number("diameter_x_px"), math_y = marker.number("diameter_y_px");
    const double d_px = std::hypot(f->x_px - c->x_px, f->y_px - c->y_px);
    const double flux = f->flux / c->flux;
    const double rx = mf.dx_px / mc.dx_px, ry = mf.dy_px / mc.dy_px;
    worst_px = std::max(worst_px, d_px);
    worst_flux = std::max(worst_flux, std::abs(flux - 1));
    worst_dia = std::max({worst_dia, std::abs(rx - 1), std::abs(ry - 1)});
    for (const double ratio :
         {mc.dx_px / math_x, mc.dy_px / math_y, mf.dx_px / math_x, mf.dy_px / math_y})
      worst_math = std::max(worst_math, std::abs(ratio - 1));
    std::printf("%-20s %9.4f %9.4f %+8.4f %+8.4f %8.4f %7.4f | %7.3f %7.4f %7.4f %7.3f %7.4f %7.4f",
                id.c_str(), c->x_px, c->y_px, f->x_px - c->x_px, f->y_px - c->y_px, d_px, flux,
                mc.dx_px, rx, mc.dx_px / math_x, mc.dy_px, ry, mc.dy_px / math_y);
    if (polygonal)
      std::printf(" | %6.2f %+6.2f %+6.2f\n", deg(mc.angle_rad),
                  deg(angle_difference(mf.angle_rad, mc.angle_rad, blades)),
                  deg(angle_difference(mc.angle_rad, expected_angle, blades)));
    else
      std::printf("\n");

    EXPECT_LT(d_px, kMaxCentroidErrorPx) << id << ": centroids differ";
    EXPECT_NEAR(flux, 1.0, kMaxFluxError) << id << ": flux filmback / Cycles";
    EXPECT_NEAR(rx, 1.0, kMaxDiameterError) << id << ": x diameter filmback / Cycles";
    EXPECT_NEAR(ry, 1.0, kMaxDiameterError) << id << ": y diameter filmback / Cycles";
    EXPECT_NEAR(mc.dx_px / math_x, 1.0, kMaxDiameterError) << id << ": x diameter Cycles / math";
    EXPECT_NEAR(mc.dy_px / math_y, 1.0, kMaxDiameterError) << id << ": y diameter Cycles / math";
    EXPECT_NEAR(mf.dx_px / math_x, 1.0, kMaxDiameterError) << id << ": x diameter filmback / math";
    EXPECT_NEAR(mf.dy_px / math_y, 1.0, kMaxDiameterError) << id << ": y diameter filmback / math";
    if (polygonal) {
      EXPECT_NEAR(angle_difference(mf.angle_rad, mc.angle_rad, blades), 0, kMaxAngleErrorRad)
          << id << ": bokeh orientation filmback - Cycles";
      EXPECT_NEAR(angle_difference(mc.angle_rad, expected_angle, blades), 0, kMaxAngleErrorRad)
          << id << ": bokeh orientation Cycles - Cycles' polygon convention";
    }
  }
  std::printf(
      "max centroid difference %.4f px (limit %.2f), max flux error %.3f %% (limit %.0f %%), "
      "max diameter error %.3f %% vs Cycles and %.3f %% vs math (limit %.0f %%)\n",
      worst_px, kMaxCentroidErrorPx, 100 * worst_flux, 100 * kMaxFluxError, 100 * worst_dia,
      100 * worst_math, 100 * kMaxDiameterError);
}

INSTANTIATE_TEST_SUITE_P(Against, BlenderShot, testing::ValuesIn(kShots),
                         [](const testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param);
                         });

}  // namespace
}  // namespace fb::test
