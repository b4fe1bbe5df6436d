#include "tests/blender/shot_comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/image/image_io.h"
#include "tests/support/commands.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kBlock = 16;
// Blocks darker than this fraction of the image's mean block are measured against it.
constexpr double kDarkBlockFraction = 0.02;

double rgb_sum(const Image& image, uint32_t x, uint32_t y) {
  return double(image.at(x, y, 0)) + image.at(x, y, 1) + image.at(x, y, 2);
}

}  // namespace

std::string ShotComparison::summary() const {
  char line[320];
  std::snprintf(line, sizeof line,
                "mean relative difference %.2f %% (noise floor %.2f %%), filmback/Cycles mean "
                "%.4f; worst 16x16 block %.2f %% at (%u, %u) (noise floor %.2f %%)",
                100 * mean_relative, 100 * noise_mean_relative, mean_ratio, 100 * worst_block,
                worst_block_x, worst_block_y, 100 * worst_noise_block);
  return line;
}

Image render_second_seed(const ShotRenders& renders, const fs::path& work_dir) {
  const fs::path output = work_dir / "filmback_seed1.exr";
  run_logged(quoted(FILMBACK_EXE) + " render " + quoted(work_dir / "shot.gltf") + " -o " +
                 quoted(output) + " -q --seed 1 --spp " + renders.shot.text("samples"),
             work_dir / "filmback_seed1.log");
  return read_image(output);
}

ShotComparison compare_shot(const Image& c, const Image& f, const Image& f1) {
  if (c.width != f.width || c.height != f.height || f1.width != f.width || f1.height != f.height ||
      c.channels.size() < 3 || f.channels.size() < 3 || f1.channels.size() < 3)
    throw std::runtime_error("compare_shot: the renders differ in size or have no RGB");
  ShotComparison s;
  double sum_abs = 0, sum_noise = 0, sum_c = 0, sum_f = 0;
  for (uint32_t y = 0; y < c.height; ++y)
    for (uint32_t x = 0; x < c.width; ++x)
      for (size_t ch = 0; ch < 3; ++ch) {
        s.finite = s.finite && std::isfinite(f.at(x, y, ch));
        sum_abs += std::abs(f.at(x, y, ch) - c.at(x, y, ch));
        sum_noise += std::abs(f.at(x, y, ch) - f1.at(x, y, ch));
        sum_c += c.at(x, y, ch), sum_f += f.at(x, y, ch);
      }
  s.mean_relative = sum_abs / sum_c;
  s.noise_mean_relative = sum_noise / sum_c;
  s.mean_ratio = sum_f / sum_c;

  const double dark = kDarkBlockFraction * sum_c / (double(c.width) * c.height) * kBlock * kBlock;
  for (uint32_t by = 0; by + kBlock <= c.height; by += kBlock)
    for (uint32_t bx = 0; bx + kBlock <= c.width; bx += kBlock) {
      double bc = 0, bf = 0, bf1 = 0;
      for (uint32_t y = by; y < by + kBlock; ++y)
        for (uint32_t x = bx; x < bx + kBlock; ++x)
          bc += rgb_sum(c, x, y), bf += rgb_sum(f, x, y), bf1 += rgb_sum(f1, x, y);
      const double reference = std::max(bc, dark);
      s.worst_noise_block = std::max(s.worst_noise_block, std::abs(bf1 - bf) / reference);
      const double d = std::abs(bf - bc) / reference;
      if (d > s.worst_block) s.worst_block = d, s.worst_block_x = bx, s.worst_block_y = by;
    }
  return s;
}

}  // namespace fb::test
