#include "core/film/film.h"

#include <cmath>

namespace fb {

Film::Film(uint32_t width, uint32_t height, std::vector<std::string> channels)
    : width_(width),
      height_(height),
      channels_(std::move(channels)),
      sums_(size_t(width) * height * channels_.size(), 0.0),
      weights_(size_t(width) * height, 0.0) {}

bool Film::add(uint32_t x, uint32_t y, const float* values, float weight) {
  const size_t n = channels_.size();
  if (!std::isfinite(weight)) return false;
  for (size_t c = 0; c < n; ++c)
    if (!std::isfinite(values[c])) return false;
  const size_t pixel = size_t(y) * width_ + x;
  double* sum = &sums_[pixel * n];
  for (size_t c = 0; c < n; ++c) sum[c] += double(weight) * values[c];
  weights_[pixel] += weight;
  return true;
}

Image Film::resolve() const {
  Image image{width_, height_, channels_, std::vector<float>(sums_.size(), 0.f)};
  const size_t n = channels_.size();
  for (size_t pixel = 0; pixel < weights_.size(); ++pixel) {
    if (weights_[pixel] == 0.0) continue;  // no sample landed: stays zero, never NaN
    for (size_t c = 0; c < n; ++c)
      image.pixels[pixel * n + c] = float(sums_[pixel * n + c] / weights_[pixel]);
  }
  return image;
}

}  // namespace fb
