// Accumulates filter-weighted samples per pixel and resolves them to the weighted mean
// sum(w_i v_i) / sum(w_i), the estimator of the measurement equation's filter integral when the
// positions are drawn from the filter (pbrt 4e §5.4.3). Each sample lands in its own pixel, so
// tiles never share a pixel and the sum order is fixed: bit-identical images for any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/image/image.h"

namespace fb {

class Film {
 public:
  Film(uint32_t width, uint32_t height, std::vector<std::string> channels);

  // Adds one sample to pixel (x, y). A sample with any non-finite value is dropped (returns
  // false) so that no NaN or Inf ever reaches the image; the caller counts them.
  bool add(uint32_t x, uint32_t y, const float* values, float weight);
  Image resolve() const;

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  const std::vector<std::string>& channels() const { return channels_; }

 private:
  uint32_t width_, height_;
  std::vector<std::string> channels_;
  // Per pixel and channel, and per pixel; double keeps high sample counts exact. Allocated
  // uninitialised and zeroed in parallel: at 1 spp, touching ~100 MB from one thread would
  // cost as much as tracing the image.
  std::unique_ptr<double[]> sums_;
  std::unique_ptr<double[]> weights_;
};

}  // namespace fb
