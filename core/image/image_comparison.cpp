#include "core/image/image_comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fb {
namespace {

constexpr uint32_t kBlock = 16;
// Blocks darker than this fraction of the image's mean block are measured against it.
constexpr double kDarkBlockFraction = 0.02;

double rgb_sum(const Image& image, uint32_t x, uint32_t y) {
  return double(image.at(x, y, 0)) + image.at(x, y, 1) + image.at(x, y, 2);
}

}  // namespace

std::string ImageComparison::summary() const {
  char line[320];
  std::snprintf(line, sizeof line,
                "mean relative difference %.2f %% (noise floor %.2f %%), mean ratio %.4f; worst "
                "16x16 block %.2f %% at (%u, %u), ratio %.3f (noise floor %.2f %%)",
                100 * mean_relative, 100 * noise_mean_relative, mean_ratio, 100 * worst_block,
                worst_block_x, worst_block_y, worst_block_ratio, 100 * worst_noise_block);
  return line;
}

ImageComparison compare_images(const Image& r, const Image& x, const Image& t) {
  if (r.width != x.width || r.height != x.height || t.width != x.width || t.height != x.height ||
      r.channels.size() < 3 || x.channels.size() < 3 || t.channels.size() < 3)
    throw std::invalid_argument("compare_images: the images differ in size or have no RGB");
  ImageComparison s;
  double sum_abs = 0, sum_noise = 0, sum_r = 0, sum_x = 0;
  for (uint32_t y = 0; y < r.height; ++y)
    for (uint32_t px = 0; px < r.width; ++px)
      for (size_t ch = 0; ch < 3; ++ch) {
        s.finite = s.finite && std::isfinite(x.at(px, y, ch));
        sum_abs += std::abs(x.at(px, y, ch) - r.at(px, y, ch));
        sum_noise += std::abs(x.at(px, y, ch) - t.at(px, y, ch));
        sum_r += r.at(px, y, ch), sum_x += x.at(px, y, ch);
      }
  s.mean_relative = sum_abs / sum_r;
  s.noise_mean_relative = sum_noise / sum_r;
  s.mean_ratio = sum_x / sum_r;

  const double dark = kDarkBlockFraction * sum_r / (double(r.width) * r.height) * kBlock * kBlock;
  for (uint32_t block_y = 0; block_y + kBlock <= r.height; block_y += kBlock)
    for (uint32_t block_x = 0; block_x + kBlock <= r.width; block_x += kBlock) {
      double block_r = 0, block_x_sum = 0, block_t = 0;
      for (uint32_t y = block_y; y < block_y + kBlock; ++y)
        for (uint32_t px = block_x; px < block_x + kBlock; ++px)
          block_r += rgb_sum(r, px, y), block_x_sum += rgb_sum(x, px, y),
              block_t += rgb_sum(t, px, y);
      const double against = std::max(block_r, dark);
      s.worst_noise_block =
          std::max(s.worst_noise_block, std::abs(block_t - block_x_sum) / against);
      const double d = std::abs(block_x_sum - block_r) / against;
      if (d > s.worst_block) {
        s.worst_block = d, s.worst_block_x = block_x, s.worst_block_y = block_y;
        s.worst_block_ratio = block_r > 0 ? block_x_sum / block_r : 0;
      }
    }
  return s;
}

}  // namespace fb
