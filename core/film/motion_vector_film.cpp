#include "core/film/motion_vector_film.h"

#include <cmath>
#include <string>

namespace fb {

MotionVectorFilm::MotionVectorFilm(uint32_t width, uint32_t height)
    : width_(width),
      height_(height),
      sums_(size_t(width) * height * 4, 0.0),
      weights_(size_t(width) * height, 0.0) {}

void MotionVectorFilm::add(uint32_t x, uint32_t y, const std::array<float, 4>& motion,
                           float weight) {
  if (!std::isfinite(weight)) return;
  for (const float m : motion)
    if (!std::isfinite(m)) return;
  const size_t pixel = size_t(y) * width_ + x;
  for (size_t c = 0; c < 4; ++c)
    sums_[pixel * 4 + c] += double(weight) * motion[c];
  weights_[pixel] += weight;
}

void MotionVectorFilm::append_pass(Image& image, std::string_view view_layer) const {
  const size_t first = image.channels.size();
  std::vector<std::string> names;
  for (const char c : {'X', 'Y', 'Z', 'W'})
    names.push_back(std::string(view_layer) + ".Vector." + c);
  append_channels(image, names);
  const size_t n = image.channels.size();
  for (size_t pixel = 0; pixel < size_t(width_) * height_; ++pixel) {
    if (weights_[pixel] == 0.0) continue;  // nothing hit: 0, as Cycles' background
    for (size_t c = 0; c < 4; ++c)
      image.pixels[pixel * n + first + c] = float(sums_[pixel * 4 + c] / weights_[pixel]);
  }
}

}  // namespace fb
