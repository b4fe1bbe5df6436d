// How `filmback bench` measures error and convergence (docs/cli.md, "bench"): errors of an image
// against a reference over the colour channels, the reference's own noise, and the least-squares
// line through log error against log time.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/image/image.h"

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

// The R, G and B channels of `image` (InputError naming `file` when it lacks one of them).
Image colour_channels(const Image& image, const std::string& file);

// `image` against `reference`, both colour_channels() images of the same size.
ImageError image_error(const Image& image, const Image& reference);

// The mean of two renders with independent seeds, and the error of that mean against the
// expected image: with A and B independent and equally noisy, E[(A - B)²] = 2σ² while the mean
// (A + B)/2 has variance σ²/2, so its MSE (and relMSE) is a quarter of A's against B, its RMSE
// half of it, and its largest error is estimated as half the largest |A - B|.
struct AveragedReference {
  Image image;
  ImageError noise;
};
AveragedReference average_halves(const Image& a, const Image& b);

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
