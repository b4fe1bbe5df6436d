// An image against a reference image of the same shot, as renders from two renderers are compared
// (tests/blender against Cycles, `filmback bench` its references): relative differences of linear
// RGB over the whole image and per 16x16 block, beside the same differences that noise alone gives
// (the noise floor), measured against a "noise twin": an image whose difference from `image` is
// distributed as the noise in `image` - `reference` (a second render of another seed when the
// reference is about as noisy as the image; see bench_metrics.h for references made of halves).
#pragma once

#include <cstdint>
#include <string>

#include "core/image/image.h"

namespace fb {

struct ImageComparison {
  // Over all pixels and R, G, B, x the image, r the reference, t the twin:
  // Σ|x − r| / Σr, and its noise floor Σ|x − t| / Σr.
  double mean_relative = 0, noise_mean_relative = 0;
  double mean_ratio = 0;  // Σx / Σr
  // Per 16x16 block, of the block's channel sums X, R, T: |X − R| / R, the worst block, where it is
  // (its top-left pixel) and X / R there; and the worst block of |X − T| / R, its noise floor. A
  // block darker than 2 % of the image's mean block is measured against that instead, so that
  // light where the reference has none still counts.
  double worst_block = 0, worst_noise_block = 0;
  uint32_t worst_block_x = 0, worst_block_y = 0;
  double worst_block_ratio = 0;
  bool finite = true;  // every R, G, B value of `image` is finite
  // One line: the numbers above, in %.
  std::string summary() const;
};

// The first three channels (R, G, B) of each; std::invalid_argument when their sizes differ or
// one has fewer than three channels.
ImageComparison compare_images(const Image& reference, const Image& image, const Image& noise_twin);

}  // namespace fb
