#include "tests/support/blobs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <iterator>
#include <stdexcept>
#include <string>

namespace fb::test {
namespace {

std::vector<double> rgb_sum(const Image& image) {
  std::array<size_t, 3> index{};
  const std::array<const char*, 3> names = {"R", "G", "B"};
  for (size_t c = 0; c < 3; ++c) {
    const auto it = std::find(image.channels.begin(), image.channels.end(), names[c]);
    if (it == image.channels.end())
      throw std::runtime_error(std::string("image has no channel ") + names[c]);
    index[c] = size_t(std::distance(image.channels.begin(), it));
  }
  std::vector<double> sum(size_t(image.width) * image.height);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      sum[size_t(y) * image.width + x] =
          double(image.at(x, y, index[0])) + image.at(x, y, index[1]) + image.at(x, y, index[2]);
  return sum;
}

}  // namespace

std::vector<Blob> find_blobs(const Image& image, double threshold) {
  const std::vector<double> value = rgb_sum(image);
  const auto w = int64_t(image.width), h = int64_t(image.height);
  std::vector<bool> seen(value.size(), false);
  std::vector<Blob> blobs;
  std::vector<int64_t> stack;  // an explicit stack: a large blob cannot overflow the call stack
  for (int64_t start = 0; start < int64_t(value.size()); ++start) {
    if (seen[size_t(start)] || !(value[size_t(start)] > threshold)) continue;
    Blob blob;
    double sum_x = 0, sum_y = 0;
    seen[size_t(start)] = true;
    stack.push_back(start);
    while (!stack.empty()) {
      const int64_t p = stack.back();
      stack.pop_back();
      const int64_t x = p % w, y = p / w;
      const double v = value[size_t(p)];
      blob.flux += v;
      sum_x += v * (double(x) + 0.5);
      sum_y += v * (double(y) + 0.5);
      blob.pixels.push_back({uint32_t(x), uint32_t(y), v});
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dx = -1; dx <= 1; ++dx) {
          const int64_t nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const int64_t q = ny * w + nx;
          if (seen[size_t(q)] || !(value[size_t(q)] > threshold)) continue;
          seen[size_t(q)] = true;
          stack.push_back(q);
        }
    }
    blob.x_px = sum_x / blob.flux;
    blob.y_px = sum_y / blob.flux;
    blobs.push_back(std::move(blob));
  }
  return blobs;
}

const Blob* nearest_blob(const std::vector<Blob>& blobs, double x_px, double y_px,
                         double within_px) {
  const Blob* best = nullptr;
  double best_px = within_px;
  for (const Blob& blob : blobs)
    if (const double d = std::hypot(blob.x_px - x_px, blob.y_px - y_px); d < best_px)
      best = &blob, best_px = d;
  return best;
}

Spread spread(const Blob& blob) {
  Spread s;
  for (const BlobPixel& p : blob.pixels) {
    const double dx = p.x + 0.5 - blob.x_px, dy = p.y + 0.5 - blob.y_px;
    s.xx += p.value * dx * dx;
    s.yy += p.value * dy * dy;
  }
  s.xx /= blob.flux;
  s.yy /= blob.flux;
  return s;
}

double streak_length_px(const Blob& blob, double ux, double uy) {
  double along = 0, across = 0;
  for (const BlobPixel& p : blob.pixels) {
    const double dx = p.x + 0.5 - blob.x_px, dy = p.y + 0.5 - blob.y_px;
    along += p.value * (dx * ux + dy * uy) * (dx * ux + dy * uy);
    across += p.value * (dx * uy - dy * ux) * (dx * uy - dy * ux);
  }
  return std::sqrt(std::max(0.0, 12 * (along - across) / blob.flux));
}

double disk_diameter_px(double spread_px2) {
  return 4 * std::sqrt(std::max(0.0, spread_px2 - 1.0 / 12));
}

double orientation_rad(const Blob& blob, unsigned n) {
  std::complex<double> moment = 0;
  for (const BlobPixel& p : blob.pixels)
    moment += p.value *
              std::pow(std::complex<double>(p.x + 0.5 - blob.x_px, p.y + 0.5 - blob.y_px), int(n));
  return std::arg(moment) / n;
}

}  // namespace fb::test
