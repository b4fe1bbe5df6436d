#include "core/film/film.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <filmback/render_passes.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fb {

Film::Film(uint32_t width, uint32_t height, std::vector<std::string> channels)
    : width_(width),
      height_(height),
      channels_(std::move(channels)),
      sums_(size_t(width) * height * channels_.size()),
      weights_(size_t(width) * height),
      counts_(size_t(width) * height) {
  for (size_t c = 0; c < channels_.size(); ++c)
    if (channel_filtering(channels_[c]) == PassFiltering::kNearest) nearest_channels_.push_back(c);
  if (!nearest_channels_.empty())
    nearest_.assign(pixel_count() * nearest_channels_.size(),
                    std::numeric_limits<float>::infinity());
}

bool Film::add(uint32_t x, uint32_t y, const float* values, float weight) {
  const size_t n = channels_.size();
  if (!std::isfinite(weight)) return false;
  for (size_t c = 0; c < n; ++c)
    if (!std::isfinite(values[c])) return false;
  const size_t pixel = size_t(y) * width_ + x;
  double* sum = &sums_[pixel * n];
  for (size_t c = 0; c < n; ++c)
    sum[c] += double(weight) * values[c];
  weights_[pixel] += weight;
  for (size_t k = 0; k < nearest_channels_.size(); ++k) {
    float& nearest = nearest_[pixel * nearest_channels_.size() + k];
    nearest = std::min(nearest, values[nearest_channels_[k]]);
  }
  return true;
}

void Film::add_sums(uint32_t x, uint32_t y, const double* sums, double weight) {
  const size_t n = channels_.size();
  const size_t pixel = size_t(y) * width_ + x;
  for (size_t c = 0; c < n; ++c)
    sums_[pixel * n + c] += sums[c];
  weights_[pixel] += weight;
}

void Film::set_sample_count(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint32_t count) {
  for (uint32_t y = y0; y < y1; ++y)
    std::fill_n(&counts_[size_t(y) * width_ + x0], x1 - x0, count);
}

Image Film::resolve() const {
  const size_t n = channels_.size(), values = pixel_count() * n;
  Image image{width_, height_, channels_, {}};
  // std::vector zeroes what it allocates from one thread: on huge pages that is a few dozen page
  // faults instead of one per 4 KiB (zeroed_pages.h).
  image.pixels.reserve(values);
  advise_huge_pages(image.pixels.data(), values * sizeof(float));
  image.pixels.resize(values);
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, pixel_count()), [&](const tbb::blocked_range<size_t>& pixels) {
        for (size_t pixel = pixels.begin(); pixel != pixels.end(); ++pixel) {
          if (weights_[pixel] == 0.0) continue;  // no sample landed: stays zero, never NaN
          for (size_t c = 0; c < n; ++c)
            image.pixels[pixel * n + c] = float(sums_[pixel * n + c] / weights_[pixel]);
          for (size_t k = 0; k < nearest_channels_.size(); ++k)
            image.pixels[pixel * n + nearest_channels_[k]] =
                nearest_[pixel * nearest_channels_.size() + k];
        }
      });
  return image;
}

}  // namespace fb
