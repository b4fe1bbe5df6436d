// Cycles' panoramic cameras against Cycles itself, one test per shot of pano_shot.py: Debian's
// Blender builds the shot (emissive markers over the frame, near a fisheye's rim, the poles and
// an equirectangular seam, on a dim uniform world), exports it through filmback's add-on and
// renders it with Cycles; filmback renders the export with the same 1 px box and sample count.
//  - each marker's centroid agrees within 0.1 px and its blob's diameters along x and y (blobs.h:
//    from its second moments; a defocused marker's blur) within 3 %, the world's radiance taken
//    off first;
//  - the lit part of the frame agrees: a pixel black in one render and lit in the other lies on
//    the edge of Cycles' lit region (a fisheye's circle cuts it), and filmback's pixels are finite.
// Noise floor (docs/camera-model.md, "Panoramic cameras"): two Cycles renders of a shot with
// different seeds put the centroids at most ~0.02 px apart at these 64 spp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/blender/blender_shot.h"
#include "tests/support/blobs.h"

namespace fb::test {
namespace {

constexpr double kMaxCentroidErrorPx = 0.1;
constexpr double kMaxDiameterError = 0.03;
// A blob belongs to a marker when its centroid is this close to where the projection images the
// marker's centre (pano_shot.py); markers are > 8 px apart and their images off-centre by < 1 px.
constexpr double kMatchRadiusPx = 2.0;

// One per entry of SHOTS in pano_shot.py.
const char* const kShots[] = {"equirectangular", "fisheye_equidistant", "fisheye_equisolid",
                              "mirrorball",      "fisheye_polynomial",  "equirectangular_dof"};

// The image with the world's radiance (R+G+B = world) taken off each pixel, so that the world is
// black and a blob's centroid weighs only its marker's light.
Image without_world(Image image, double world) {
  for (float& v : image.pixels)
    v = std::max(0.f, v - float(world / 3));
  return image;
}

bool lit(const Image& image, uint32_t x, uint32_t y) {
  return image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2) > 0;
}

// A pixel on the edge of the lit region: it or one of its 8 neighbours is lit and another not.
bool on_edge(const Image& image, uint32_t x, uint32_t y) {
  bool any_lit = false, any_dark = false;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int64_t nx = int64_t(x) + dx, ny = int64_t(y) + dy;
      if (nx < 0 || ny < 0 || nx >= image.width || ny >= image.height) continue;
      (lit(image, uint32_t(nx), uint32_t(ny)) ? any_lit : any_dark) = true;
    }
  return any_lit && any_dark;
}

class BlenderPanorama : public WithBlender<testing::TestWithParam<const char*>> {};

TEST_P(BlenderPanorama, MarkersAndCircleMatchCycles) {
  const std::string name = GetParam();
  const ShotRenders r =
      render_shot(blender, name, std::filesystem::path(FILMBACK_BLENDER_WORK_DIR) / name,
                  FILMBACK_PANO_SHOT_PY);
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
  EXPECT_EQ(r.filmback_log.find("warning:"), std::string::npos) << r.filmback_log;

  size_t non_finite = 0, disagree = 0, lit_cycles = 0;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      for (size_t c = 0; c < 3; ++c)
        non_finite += !std::isfinite(r.filmback.at(x, y, c));
      lit_cycles += lit(r.cycles, x, y);
      if (lit(r.cycles, x, y) != lit(r.filmback, x, y) && !on_edge(r.cycles, x, y)) {
        ++disagree;
        ADD_FAILURE() << "pixel (" << x << ", " << y << ") is "
                      << (lit(r.cycles, x, y) ? "" : "not ") << "lit in Cycles' render and "
                      << (lit(r.filmback, x, y) ? "" : "not ")
                      << "in filmback's, away from the lit region's edge";
      }
    }
  EXPECT_EQ(non_finite, 0u) << "non-finite values in filmback's render";

  const double world = r.shot.number("world");
  const std::vector<Blob> cycles_blobs = find_blobs(without_world(r.cycles, world), 1e-4);
  const std::vector<Blob> filmback_blobs = find_blobs(without_world(r.filmback, world), 1e-4);
  EXPECT_EQ(cycles_blobs.size(), r.markers.size()) << "blobs in the Cycles render";
  EXPECT_EQ(filmback_blobs.size(), r.markers.size()) << "blobs in the filmback render";
  std::printf(
      "Shot %s: %ux%u at %s spp; Blender %.1f s (Cycles %.1f s), filmback %.1f s; %zu of "
      "%u pixels lit in Cycles' render\n",
      name.c_str(), width, height, r.shot.text("samples").c_str(), r.blender_s, r.cycles_s,
      r.filmback_s, lit_cycles, width * height);
  std::printf("%-18s %9s %9s %8s %8s %8s %7s\n", "marker", "cycles_x", "cycles_y", "dx_px", "dy_px",
              "|d|_px", "flux");
  double worst_px = 0, worst_dia = 0;
  for (const Record& marker : r.markers) {
    const std::string& id = marker.text("name");
    const double x = marker.number("image_x_px"), y = marker.number("image_y_px");
    const Blob* c = nearest_blob(cycles_blobs, x, y, kMatchRadiusPx);
    const Blob* f = nearest_blob(filmback_blobs, x, y, kMatchRadiusPx);
    if (!c || !f) {
      ADD_FAILURE() << id << ": no " << (c ? "filmback" : "Cycles") << " blob within "
                    << kMatchRadiusPx << " px of where the projection images it (" << x << ", " << y
                    << ")";
      continue;
    }
    const double d_px = std::hypot(f->x_px - c->x_px, f->y_px - c->y_px);
    worst_px = std::max(worst_px, d_px);
    const Spread sc = spread(*c), sf = spread(*f);
    const double cx = disk_diameter_px(sc.xx), cy = disk_diameter_px(sc.yy);
    const double rx = disk_diameter_px(sf.xx) / cx, ry = disk_diameter_px(sf.yy) / cy;
    worst_dia = std::max({worst_dia, std::abs(rx - 1), std::abs(ry - 1)});
    std::printf("%-18s %9.4f %9.4f %+8.4f %+8.4f %8.4f %7.4f | %7.3f %7.4f %7.3f %7.4f\n",
                id.c_str(), c->x_px, c->y_px, f->x_px - c->x_px, f->y_px - c->y_px, d_px,
                f->flux / c->flux, cx, rx, cy, ry);
    EXPECT_LT(d_px, kMaxCentroidErrorPx) << id << ": centroids differ";
    EXPECT_NEAR(rx, 1.0, kMaxDiameterError) << id << ": x diameter filmback / Cycles";
    EXPECT_NEAR(ry, 1.0, kMaxDiameterError) << id << ": y diameter filmback / Cycles";
  }
  std::printf(
      "max centroid difference %.4f px (limit %.2f), max diameter error %.2f %% (limit %.0f %%); "
      "%zu pixels lit in one render only away from the edge\n",
      worst_px, kMaxCentroidErrorPx, 100 * worst_dia, 100 * kMaxDiameterError, disagree);
}

INSTANTIATE_TEST_SUITE_P(Against, BlenderPanorama, testing::ValuesIn(kShots),
                         [](const testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param);
                         });

}  // namespace
}  // namespace fb::test
