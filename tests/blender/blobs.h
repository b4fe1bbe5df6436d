// Bright blobs on a black image: connected components of the pixels whose R+G+B exceeds a
// threshold, with their flux-weighted centroid. The alignment test measures each render with it.
#pragma once

#include <cstddef>
#include <vector>

#include "core/image/image.h"

namespace fb::test {

struct Blob {
  double x_px = 0, y_px = 0;  // flux-weighted centroid; raster convention, pixel centres at i + 0.5
  double flux = 0;            // sum over the blob's pixels of R+G+B
  size_t pixel_count = 0;
};

// 8-connected components of the pixels with R+G+B > threshold, in raster order of their first
// pixel. Channels are found by name; throws std::runtime_error if R, G or B is missing.
std::vector<Blob> find_blobs(const Image& image, double threshold);

}  // namespace fb::test
