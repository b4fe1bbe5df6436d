// Blender's Vector pass (docs/blender.md, "Passes") resolved as Cycles 3.4 resolves it: per pixel,
// the filter-weighted mean of the motion of the samples whose camera ray met something. A miss
// adds to neither sum (Cycles keeps a motion weight beside the pass for this), so an edge pixel
// keeps the moving object's vector instead of a share of it, and a pixel no sample hit is 0.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/image/image.h"

namespace fb {

class MotionVectorFilm {
 public:
  MotionVectorFilm(uint32_t width, uint32_t height);

  // One sample of pixel (x, y) that hit something, with its motion (X, Y, Z, W, pixels) and its
  // filter weight. A non-finite value or weight is dropped, as the film drops such samples.
  void add(uint32_t x, uint32_t y, const std::array<float, 4>& motion, float weight);

  // Appends "<view_layer>.Vector.X/Y/Z/W" to `image` (its size).
  void append_pass(Image& image, std::string_view view_layer) const;

 private:
  uint32_t width_, height_;
  std::vector<double> sums_;     // per pixel, X, Y, Z, W
  std::vector<double> weights_;  // per pixel, of the samples that hit
};

}  // namespace fb
