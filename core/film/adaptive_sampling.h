// Adaptive sampling as Cycles does it by default (docs/sampling.md, "Adaptive sampling"): beside
// the film's sums, a second accumulation of every other sample (the half buffer A); from the
// difference of the whole estimate I and A, a per-pixel error |I - A| / sqrt(I), checked every
// `kStep` samples once `min_samples` are taken. A pixel whose error, and its eight neighbours'
// errors, are below the threshold has converged: it takes no more samples.
//
// Cycles' sources: intern/cycles/kernel/film/adaptive_sampling.h (the error and the neighbours'
// box filter) and intern/cycles/scene/integrator.cpp (get_adaptive_sampling: the automatic
// minimum, the factor 5 on the threshold, the step of 16). The error is section 2.1 of Dammertz
// et al., "A hierarchical automatic stopping condition for Monte Carlo global illumination"
// (WSCG 2010).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>

#include "core/film/film.h"

namespace fb {

// What a render asks for: a threshold > 0 turns adaptive sampling on.
struct AdaptiveRequest {
  double threshold = 0;      // Cycles' adaptive_threshold, as Blender shows it
  uint32_t min_samples = 0;  // Cycles' adaptive_min_samples; 0: automatic
};

// The settings a render samples with, from a request as Cycles derives them.
struct AdaptiveSettings {
  double threshold = 0;      // compared with the error: the request's times Cycles' factor 5
  uint32_t min_samples = 0;  // no pixel stops before this many samples
};

// Cycles' checks come every 16 samples (integrator.cpp, adaptive_step); ours too, so that the
// sample counts a pixel can stop at are the same.
constexpr uint32_t kAdaptiveStep = 16;

// None when the request's threshold is 0 (off). An automatic minimum is Cycles' guess
// ceil(16 / threshold^0.3), at least 4 (threshold 0.01: 64 samples).
std::optional<AdaptiveSettings> adaptive_settings(const AdaptiveRequest& request);

// Whether a check is due once every unconverged pixel has `samples` samples.
inline bool adaptive_check_due(const AdaptiveSettings& s, uint32_t samples) {
  return samples >= s.min_samples && samples % kAdaptiveStep == 0;
}

// The checks a render of `samples_per_pixel` makes: one at each due count below it (at the last
// sample nothing is left to stop). After k checks a pixel's flag depends on pixels up to k away
// (each check looks at the 3x3 neighbourhood, whose own samples depend on the checks before), so
// a part of a render samples an apron this wide around its crop (render_loop.h, part_region).
uint32_t adaptive_check_count(const AdaptiveSettings& s, uint32_t samples_per_pixel);

// The half buffer and each pixel's converged flag, for a film whose first three channels are
// R, G, B. Each pixel is written by the one tile that holds it, so no locks are needed.
class ConvergenceMap {
 public:
  ConvergenceMap(uint32_t width, uint32_t height, const AdaptiveSettings& settings,
                 double exposure);

  // Sample `sample_index` of pixel (x, y), as the film took it: the odd indices are A's half
  // (Cycles' film/write.h keeps every other sample, doubled, in its aux pass).
  void add(uint32_t x, uint32_t y, uint32_t sample_index, const float* rgb, float weight);
  bool converged(uint32_t x, uint32_t y) const { return converged_[index(x, y)] != 0; }

  // Marks converged every unconverged pixel whose error, and whose neighbours' errors (a pixel
  // already converged counts as below), are below the threshold: Cycles' filter_x and filter_y
  // let a noisy pixel's neighbours go on sampling. A converged pixel stays converged, so that its
  // samples stay the indices 0 .. n-1 of its sequence. `on_converged(x, y)` is called for each
  // pixel that converges now. The result depends on the film's sums only: deterministic.
  // `samples` is the count the unconverged pixels have reached: the check's, which a resumed
  // render must not make again (checked_samples).
  template <typename OnConverged>
  void update(const Film& film, uint32_t samples, const OnConverged& on_converged);

  // The error of pixel (x, y): the sum over R, G, B of |I - A|, over sqrt(R + G + B) of I (or
  // R + G + B itself above 1, as Cycles: brighter pixels need less), times the exposure.
  double error(const Film& film, uint32_t x, uint32_t y) const;

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

  // The raw state, for checkpoints (core/film/convergence_exr.h), rows top first: per pixel the
  // odd samples' 3 sums of w v and their sum of w, and the converged flag (0 or 1); and the sample
  // count of the last check made (0: none yet).
  double* half_sums() { return half_sums_.get(); }
  double* half_weights() { return half_weights_.get(); }
  uint8_t* converged_flags() { return converged_.get(); }
  const double* half_sums() const { return half_sums_.get(); }
  const double* half_weights() const { return half_weights_.get(); }
  const uint8_t* converged_flags() const { return converged_.get(); }
  uint32_t checked_samples() const { return checked_samples_; }
  void set_checked_samples(uint32_t samples) { checked_samples_ = samples; }

 private:
  size_t index(uint32_t x, uint32_t y) const { return size_t(y) * width_ + x; }
  bool below_threshold(const Film& film, uint32_t x, uint32_t y) const;

  uint32_t width_, height_;
  AdaptiveSettings settings_;
  double exposure_;
  std::unique_ptr<double[]> half_sums_;     // 3 per pixel: the odd samples' sum of w v
  std::unique_ptr<double[]> half_weights_;  // the odd samples' sum of w
  std::unique_ptr<uint8_t[]> converged_;
  std::unique_ptr<uint8_t[]> below_;  // scratch for update()
  uint32_t checked_samples_ = 0;
};

template <typename OnConverged>
void ConvergenceMap::update(const Film& film, uint32_t samples, const OnConverged& on_converged) {
  checked_samples_ = samples;
  for (uint32_t y = 0; y < height_; ++y)
    for (uint32_t x = 0; x < width_; ++x)
      below_[index(x, y)] = converged(x, y) || below_threshold(film, x, y);
  for (uint32_t y = 0; y < height_; ++y)
    for (uint32_t x = 0; x < width_; ++x) {
      if (converged(x, y)) continue;
      bool all_below = true;
      for (uint32_t ny = y > 0 ? y - 1 : 0; ny <= std::min(y + 1, height_ - 1); ++ny)
        for (uint32_t nx = x > 0 ? x - 1 : 0; nx <= std::min(x + 1, width_ - 1); ++nx)
          all_below = all_below && below_[index(nx, ny)];
      if (!all_below) continue;
      converged_[index(x, y)] = 1;
      on_converged(x, y);
    }
}

}  // namespace fb
