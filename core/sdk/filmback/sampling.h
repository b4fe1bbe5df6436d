// Sample warps and a tabulated 1-D distribution, shared by plugins and the core.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "vec.h"

namespace fb {

// Shirley & Chiu's concentric map from [0,1)^2 onto the unit disk: area-preserving and with low
// distortion, so stratified samples stay stratified (pbrt 4e §A.5.1).
inline Vec2f sample_concentric_disk(Vec2f u) {
  const float ox = 2.f * u.x - 1.f, oy = 2.f * u.y - 1.f;
  if (ox == 0.f && oy == 0.f) return {0.f, 0.f};
  constexpr float kPiOver4 = std::numbers::pi_v<float> / 4.f;
  if (std::abs(ox) > std::abs(oy)) {
    const float theta = kPiOver4 * (oy / ox);
    return {ox * std::cos(theta), ox * std::sin(theta)};
  }
  const float theta = 2.f * kPiOver4 - kPiOver4 * (ox / oy);
  return {oy * std::cos(theta), oy * std::sin(theta)};
}

// Malley's method: project disk samples up onto the hemisphere; pdf = cos(theta) / pi.
inline Vec3f sample_cosine_hemisphere(Vec2f u) {
  const Vec2f d = sample_concentric_disk(u);
  const float z = std::sqrt(std::max(0.f, 1.f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

// Uniform barycentrics on a triangle (Heitz 2019, "A Low-Distortion Map Between Triangle and
// Square"): returns (b0, b1) with b2 = 1 - b0 - b1.
inline Vec2f sample_uniform_triangle(Vec2f u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2.f;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2.f;
    b0 = u.x - b1;
  }
  return {b0, b1};
}

// Veach's power heuristic (beta = 2) for two strategies with one sample each, written as
// 1 / (1 + (b/a)^2) so that large pdfs (grazing angles, tiny emitters) cannot overflow to inf/inf.
inline float power_heuristic(float pdf_a, float pdf_b) {
  if (!(pdf_a > 0.f)) return 0.f;
  const float r = pdf_b / pdf_a;
  return 1.f / (1.f + r * r);
}

// A piecewise-constant distribution over [lo, hi] proportional to |f| at bin centres: the
// importance sampler for filters without an analytic inverse CDF. The sign of f is not part of
// the density; callers weight by f(x) / pdf(x), so negative lobes keep their sign.
class Tabulated1D {
 public:
  Tabulated1D(const std::function<double(double)>& f, double lo, double hi, int bins = 1024)
      : lo_(lo), width_(hi - lo), cdf_(bins + 1, 0.0) {
    for (int i = 0; i < bins; ++i) {
      const double x = lo + (i + 0.5) * width_ / bins;
      cdf_[i + 1] = cdf_[i] + std::abs(f(x));
    }
    const double total = cdf_.back();
    for (double& c : cdf_)
      c /= total;
  }

  struct Sample {
    double x;
    double pdf;
  };

  Sample sample(double u) const {
    const int bins = static_cast<int>(cdf_.size()) - 1;
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    const int i = std::clamp(static_cast<int>(it - cdf_.begin()) - 1, 0, bins - 1);
    const double mass = cdf_[i + 1] - cdf_[i];
    const double t = mass > 0.0 ? (u - cdf_[i]) / mass : 0.5;
    const double bin_width = width_ / bins;
    return {lo_ + (i + std::clamp(t, 0.0, 1.0)) * bin_width, mass / bin_width};
  }

 private:
  double lo_, width_;
  std::vector<double> cdf_;
};

}  // namespace fb
