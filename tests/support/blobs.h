// Bright blobs on a black image: connected components of the pixels whose R+G+B exceeds a
// threshold, with their flux-weighted centroid, spread and orientation. The tests against Blender
// and against POV-Ray measure each render with them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/image/image.h"

namespace fb::test {

struct BlobPixel {
  uint32_t x, y;  // the pixel's index; its centre is at (x + 0.5, y + 0.5)
  double value;   // R+G+B
};

struct Blob {
  double x_px = 0, y_px = 0;  // flux-weighted centroid; raster convention, pixel centres at i + 0.5
  double flux = 0;            // sum over the blob's pixels of R+G+B
  std::vector<BlobPixel> pixels;
};

// 8-connected components of the pixels with R+G+B > threshold, in raster order of their first
// pixel. Channels are found by name; throws std::runtime_error if R, G or B is missing.
std::vector<Blob> find_blobs(const Image& image, double threshold);

// The blob whose centroid is nearest to (x_px, y_px) and closer than within_px; nullptr if none.
const Blob* nearest_blob(const std::vector<Blob>& blobs, double x_px, double y_px,
                         double within_px);

// Flux-weighted central second moments, px^2: <(x - x̄)^2> and <(y - ȳ)^2>.
struct Spread {
  double xx = 0, yy = 0;
};
Spread spread(const Blob& blob);

// The diameter of the uniform disk whose image, box-filtered into 1 px pixels, has this spread
// along one axis: a disk of diameter d has <x^2> = d^2 / 16 and the pixel's box adds 1/12 px^2
// (second moments of convolved images add). It is the blur diameter of a defocused point, and
// since moments add, squared diameters of convolved shapes add too.
double disk_diameter_px(double spread_px2);

// The length of a streak travelling along the unit direction (ux, uy): a shape convolved with a
// segment of length L has second moments along and across the segment differing by L^2 / 12
// more than the shape's own (moments add under convolution), so for an isotropic shape (a round
// emitter's image, the 1 px box) L = sqrt(12 (along - across)). 0 for a still one.
double streak_length_px(const Blob& blob, double ux, double uy);

// The angle, in (-pi/n, pi/n], of a vertex of an n-fold symmetric blob (a polygonal bokeh) from
// the phase of its complex central moment sum((z - z̄)^n) with z = x + i y (raster axes, y down):
// a regular n-gon with a vertex at angle a has the phase n a. The moment of a shape convolved
// with an isotropic one (a round emitter's image) keeps this phase exactly.
double orientation_rad(const Blob& blob, unsigned n);

}  // namespace fb::test
