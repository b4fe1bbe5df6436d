// How `filmback bench` measures error and convergence (docs/cli.md, "bench"): errors of an image
// against a reference over the colour channels, the reference's own noise, and the least-squares
// line through log error against log time.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/image/image.h"
#include "core/image/image_comparison.h"

namespace fb {

// relMSE's ε: keeps dark reference pixels from dominating the mean (Rousselle, Knaus and Zwicker
// 2011, "Adaptive Sampling and Reconstruction using Greedy Error Minimization").
constexpr double kRelMseEpsilon = 1e-2;

// Over the R, G and B channels of every pixel, x the image and r the reference:
struct ImageError {
  double rmse = 0;     // sqrt(mean (x - r)²)
  double relmse = 0;   // mean (x - r)² / (r² + ε)
  double max_abs = 0;  // max |x - r|
};

// The R, G and B channels of `image` (InputError naming `file` when it lacks one of them); an image
// of exactly R, G, B is returned as it is, so that a moved-in image keeps its one pixel buffer.
Image colour_channels(Image image, const std::string& file);

// `image` against `reference`, both colour_channels() images of the same size.
ImageError image_error(const Image& image, const Image& reference);

// The mean of two renders with independent seeds, and the error of that mean against the
// expected image: with A and B independent and equally noisy, E[(A - B)²] = 2σ² while the mean
// (A + B)/2 has variance σ²/2, so its MSE (and relMSE) is a quarter of A's against B, its RMSE
// half of it, and its largest error is estimated as half the largest |A - B|. (A - B)/2 has the
// mean's noise variance, σ²/2, without its signal: what compare_references adds to make a twin.
struct AveragedReference {
  Image image;
  ImageError noise;
  Image half_difference;  // (A - B)/2; no pixels for a reference given as one image
};
// The halves' pixel buffers become the mean's and the half difference's: move them in.
AveragedReference average_halves(Image a, Image b);

// Two renderers' references of one shot (filmback's `ours` against Cycles' `theirs`), each the mean
// of two halves: how far apart they are beyond their noise, so that measuring both renderers
// against `theirs` is known to measure convergence and not a difference of the models.
struct ReferenceAgreement {
  ImageError between;     // ours against theirs
  double noise_rmse = 0;  // what their noise alone gives: sqrt(noise_ours² + noise_theirs²)
  // Mean and per-block relative differences beside their noise floor. The twin is ours plus
  // both half differences: with independent noise, ours - theirs = bias + n_ours - n_theirs,
  // whose noise has variance (σ_ours² + σ_theirs²)/2, the variance of the sum of the half
  // differences; so |ours - twin| is what the references' difference would be without a bias.
  ImageComparison comparison;
};
ReferenceAgreement compare_references(const AveragedReference& ours,
                                      const AveragedReference& theirs);

// Issue 14's bar for filmback against Cycles (tests/blender): the mean relative difference at
// most 2 % and every 16x16 block at most 5 % above their noise floors.
constexpr double kAgreeMeanAboveNoise = 0.02;
constexpr double kAgreeBlockAboveNoise = 0.05;
inline bool references_agree(const ReferenceAgreement& a) {
  const ImageComparison& c = a.comparison;
  return c.finite && c.mean_relative <= c.noise_mean_relative + kAgreeMeanAboveNoise &&
         c.worst_block <= c.worst_noise_block + kAgreeBlockAboveNoise;
}

// log(error) = intercept + slope log(x), least squares over the points given.
struct LogLogFit {
  double slope = 0, intercept = 0;
  double x_min = 0, x_max = 0;  // the range of the points fitted
  size_t points = 0;
  // The x at which the line reaches `error`; none when the line does not fall (slope >= 0).
  std::optional<double> x_at(double error) const;
  bool extrapolates(double x) const { return x < x_min || x > x_max; }
};
// None with fewer than two distinct x.
std::optional<LogLogFit> fit_log_log(const std::vector<double>& x,
                                     const std::vector<double>& error);

}  // namespace fb
