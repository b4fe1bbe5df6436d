// Radiometry against Cycles (radiometry_shot.py): shots lit by Blender's lights and a world
// (diffuse, or with a glossy metal ground), where a Blender light of P watts must give Cycles'
// pixel values. Both renderers use the same sample count and a 1 px box filter; the comparison is
// of linear RGB.
//
// Errors are relative differences |filmback - cycles| / cycles of the three channels summed:
//   * per pixel: their mean below kMaxMeanError, over the pixels whose reference is at least
//     kDarkFraction of the image's mean (below it, a relative difference measures noise around
//     zero, not radiometry);
//   * per 16x16 block (of block sums): every block below kMaxBlockError, where a block darker than
//     that threshold is measured against the threshold instead, so that light where Cycles has
//     none (an area light seen by the camera, say) still fails.
// A shot whose noise at its sample count is above these bars has Cycles render it twice, with two
// seeds (radiometry_shot.py, Shot.noise_floor): the two Cycles images' errors against each other
// are its noise floor, and filmback's errors may exceed them by the bars. Every other shot's floor
// is taken as 0. Measured errors and floors are in docs/blender.md, "Lights and world".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "core/image/image_io.h"
#include "tests/blender/blender_shot.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxMeanError = 0.02;
constexpr double kMaxBlockError = 0.05;
constexpr uint32_t kBlock = 16;
constexpr double kDarkFraction = 0.02;

double rgb_sum(const Image& image, uint32_t x, uint32_t y) {
  return double(image.at(x, y, 0)) + image.at(x, y, 1) + image.at(x, y, 2);
}

struct Errors {
  double mean_pixel = 0, max_block = 0;
  size_t pixels = 0, blocks = 0;
};

Errors compare(const Image& filmback, const Image& cycles) {
  double total = 0;
  for (uint32_t y = 0; y < cycles.height; ++y)
    for (uint32_t x = 0; x < cycles.width; ++x)
      total += rgb_sum(cycles, x, y);
  const double dark = kDarkFraction * total / (double(cycles.width) * cycles.height);
  Errors e;
  double sum = 0;
  for (uint32_t by = 0; by + kBlock <= cycles.height; by += kBlock)
    for (uint32_t bx = 0; bx + kBlock <= cycles.width; bx += kBlock) {
      double f = 0, c = 0;
      for (uint32_t y = by; y < by + kBlock; ++y)
        for (uint32_t x = bx; x < bx + kBlock; ++x) {
          const double fp = rgb_sum(filmback, x, y), cp = rgb_sum(cycles, x, y);
          f += fp, c += cp;
          if (cp > dark) sum += std::abs(fp - cp) / cp, ++e.pixels;
        }
      e.max_block = std::max(e.max_block, std::abs(f - c) / std::max(c, dark * kBlock * kBlock));
      ++e.blocks;
    }
  e.mean_pixel = e.pixels ? sum / double(e.pixels) : 0;
  return e;
}

class BlenderRadiometry : public WithBlender<testing::TestWithParam<const char*>> {};

TEST_P(BlenderRadiometry, MatchesCycles) {
  const std::string shot = GetParam();
  const ShotRenders r =
      render_shot(blender, shot, fs::path(FILMBACK_BLENDER_WORK_DIR) / ("radiometry_" + shot),
                  FILMBACK_RADIOMETRY_SHOT_PY);
  ASSERT_EQ(r.filmback.width, r.cycles.width);
  ASSERT_EQ(r.filmback.height, r.cycles.height);
  ASSERT_GE(r.cycles.channels.size(), 3u);
  ASSERT_GE(r.filmback.channels.size(), 3u);
  const Errors e = compare(r.filmback, r.cycles);
  Errors floor;
  if (r.shot.fields.count("second_cycles")) {
    const fs::path work = fs::path(FILMBACK_BLENDER_WORK_DIR) / ("radiometry_" + shot);
    floor = compare(read_image(work / r.shot.text("second_cycles")), r.cycles);
  }
  std::printf(
      "%s: mean pixel error %.2f %% over %zu pixels, worst 16x16 block %.2f %% of %zu (noise "
      "floor: %.2f %%, %.2f %%); Blender %.1f s (Cycles %.1f s), filmback %.1f s\n",
      shot.c_str(), 100 * e.mean_pixel, e.pixels, 100 * e.max_block, e.blocks,
      100 * floor.mean_pixel, 100 * floor.max_block, r.blender_s, r.cycles_s, r.filmback_s);
  ASSERT_GT(e.pixels, 0u) << "the reference is dark everywhere";
  EXPECT_LT(e.mean_pixel, floor.mean_pixel + kMaxMeanError);
  EXPECT_LT(e.max_block, floor.max_block + kMaxBlockError);
}

INSTANTIATE_TEST_SUITE_P(Shots, BlenderRadiometry,
                         testing::Values("sun_world", "point_spot", "area", "hdr_world",
                                         "point_glossy", "sun_glossy", "spot_radius",
                                         "disk_ellipse", "spread"));

}  // namespace
}  // namespace fb::test
