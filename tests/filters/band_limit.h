// Separable image operations on a fine grid for the antialiasing measurement (docs/filters.md):
// convolution with a filter's 1-D profile, and the ideal low-pass at the coarse grid's Nyquist
// frequency, by FFT of the evenly mirrored signal (so the image's borders add no jump).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace fb::filters {

struct Grid {
  size_t width = 0, height = 0;
  std::vector<double> values;  // row-major
  double& at(size_t x, size_t y) { return values[y * width + x]; }
  double at(size_t x, size_t y) const { return values[y * width + x]; }
};

// Convolves rows and then columns with the same taps, centred: out[i] = sum_t taps[t] in[i - t +
// c], c = taps.size() / 2 (odd sizes); samples past the border repeat the edge value.
Grid convolve_separable(const Grid& in, const std::vector<double>& taps);

// Keeps the frequencies below `cutoff` cycles per sample along each axis (half weight exactly at
// it) and removes the rest: a brick-wall low-pass, separable. Each side must be a power of two.
Grid low_pass(const Grid& in, double cutoff);

}  // namespace fb::filters
