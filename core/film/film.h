// Accumulates filter-weighted samples per pixel and resolves them to the weighted mean
// sum(w_i v_i) / sum(w_i), the estimator of the measurement equation's filter integral when the
// positions are drawn from the filter (pbrt 4e §5.4.3). Each sample lands in its own pixel, so
// tiles never share a pixel and the sum order is fixed: bit-identical images for any thread count.
// Splatting forms its sums per tile (splat_tiles.h) and adds them here in a fixed order.
// Channels of a render pass resolved to the nearest sample (Depth: filmback/render_passes.h) keep
// that sample's value beside the sums, which cannot express a minimum.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/film/zeroed_pages.h"
#include "core/image/image.h"

namespace fb {

// How samples become pixels (docs/filters.md): kImportance draws each sample's offset from the
// filter and keeps it in its own pixel with weight h / pdf (this file); kSplat draws it uniformly
// over the pixel and spreads it to every pixel within the filter's radius with weight h
// (core/film/splat_tiles.h). Both resolve to a weighted mean.
enum class Reconstruction { kImportance, kSplat };
inline const char* reconstruction_name(Reconstruction r) {
  return r == Reconstruction::kSplat ? "splat" : "importance";  // as typed: --reconstruction
}

class Film {
 public:
  // The channels' filtering follows their names (fb::channel_filtering).
  Film(uint32_t width, uint32_t height, std::vector<std::string> channels);

  // Adds one sample to pixel (x, y). A sample with any non-finite value is dropped (returns
  // false) so that no NaN or Inf ever reaches the image; the caller counts them.
  bool add(uint32_t x, uint32_t y, const float* values, float weight);
  // Adds sums formed elsewhere (a splat tile's sum w v per channel, and sum w) to pixel (x, y).
  void add_sums(uint32_t x, uint32_t y, const double* sums, double weight);
  // Records that the pixels [x0, x1) x [y0, y1) have taken `count` samples (kept or dropped):
  // what an interrupted render reports per pixel and a resumed one starts from.
  void set_sample_count(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint32_t count);
  uint32_t sample_count(uint32_t x, uint32_t y) const { return counts_[size_t(y) * width_ + x]; }
  Image resolve() const;

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  const std::vector<std::string>& channels() const { return channels_; }
  size_t pixel_count() const { return size_t(width_) * height_; }

  // The raw state, for checkpoints (core/film/checkpoint.h): pixel_count() * channels().size()
  // sums, pixel_count() weights and sample counts, rows top first.
  double* sums() { return sums_.get(); }
  double* weights() { return weights_.get(); }
  uint32_t* sample_counts() { return counts_.get(); }
  const double* sums() const { return sums_.get(); }
  const double* weights() const { return weights_.get(); }
  const uint32_t* sample_counts() const { return counts_.get(); }

 private:
  uint32_t width_, height_;
  std::vector<std::string> channels_;
  // Per pixel and channel, and per pixel; double keeps high sample counts exact. Zeroed by the
  // kernel where the tile that owns a page first writes it (zeroed_pages.h): at 1 spp, zeroing
  // ~100 MB before the render, even in parallel, cost as much as tracing the image.
  ZeroedArray<double> sums_;
  ZeroedArray<double> weights_;
  ZeroedArray<uint32_t> counts_;
  std::vector<size_t> nearest_channels_;  // indices into channels_, fb::PassFiltering::kNearest
  std::vector<float> nearest_;  // per pixel and nearest channel: the least value, +inf: none yet
};

}  // namespace fb
