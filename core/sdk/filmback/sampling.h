// Sample warps and a tabulated 1-D distribution, shared by plugins and the core.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// Uniform on the unit sphere, pdf 1 / (4 pi): z uniform in [-1, 1] (Archimedes), phi in [0, 2 pi).
inline Vec3f sample_uniform_sphere(Vec2f u) {
  const float z = 1.f - 2.f * u.x;
  const float r = std::sqrt(std::max(0.f, 1.f - z * z));
  const float phi = 2.f * std::numbers::pi_v<float> * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
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

// Uniform point in the regular polygon with `blades` corners on the unit circle at angles
// rotation + (2k + 1) pi / blades, as Cycles places them (regular_polygon_sample in Cycles'
// kernel/sample/mapping.h): rotation 0 puts an edge, not a corner, across +x. A wedge chosen by
// u.x, then a uniform point in its triangle.
inline Vec2f sample_regular_polygon(Vec2f u, uint32_t blades, float rotation) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float wedge_f = u.x * float(blades);
  const uint32_t wedge = std::min(uint32_t(wedge_f), blades - 1);
  const float ux = wedge_f - float(wedge);  // the remaining bits of u.x, uniform in [0,1)
  const float a0 = rotation + kPi * float(2 * wedge + 1) / float(blades);
  const float a1 = a0 + 2.f * kPi / float(blades);
  const Vec2f b = sample_uniform_triangle({ux, u.y});  // weights of the two corners
  return {b.y * std::cos(a0) + (1.f - b.x - b.y) * std::cos(a1),
          b.y * std::sin(a0) + (1.f - b.x - b.y) * std::sin(a1)};
}

// A point of Blender's aperture of unit radius (Cycles' camera_sample_aperture): the disk, or the
// regular polygon of `blades` >= 3 blades, its x divided by the anamorphic ratio.
inline Vec2f sample_aperture(Vec2f u, uint32_t blades, float rotation, float inverse_ratio) {
  Vec2f lens = blades ? sample_regular_polygon(u, blades, rotation) : sample_concentric_disk(u);
  lens.x *= inverse_ratio;
  return lens;
}

// The schema entries (fb_param_desc, plugin_abi.h) of the aperture's shape sample_aperture takes,
// under Blender's names and ranges: every camera with Blender's depth of field declares them.
// clang-format off
#define FB_APERTURE_SHAPE_PARAMS                                                                  \
  {"aperture_blades", FB_PARAM_INT, "0", "", nullptr, 0, 64,                                      \
   "0: a round aperture; else a regular polygon of at least 3 blades"},                           \
  {"aperture_rotation_rad", FB_PARAM_FLOAT, "0", "rad", nullptr, -1e3, 1e3,                      \
   "rotation of the blades"},                                                                     \
  {"aperture_ratio", FB_PARAM_FLOAT, "1", "", nullptr, 1e-2, 1e2,                                 \
   "anamorphic bokeh: the aperture's x is divided by it"}
// clang-format on

// Veach's power heuristic (beta = 2) for two strategies with one sample each, written as
// 1 / (1 + (b/a)^2) so that large pdfs (grazing angles, tiny emitters) cannot overflow to inf/inf.
inline float power_heuristic(float pdf_a, float pdf_b) {
  if (!(pdf_a > 0.f)) return 0.f;
  const float r = pdf_b / pdf_a;
  return 1.f / (1.f + r * r);
}

// A piecewise-linear distribution over [lo, hi] proportional to |f| interpolated between
// `bins` + 1 equally spaced nodes: the importance sampler for filters without an analytic inverse
// CDF. The sign of f is not part of the density; callers weight by f(x) / pdf(x), so negative lobes
// keep their sign. Linear rather than constant pieces follow f to second order, so the weight
// f / pdf stays within about 1e-5 of constant where f does not change sign (docs/filters.md
// measures both), and f going linearly to zero at a node (a filter's edge, a zero crossing) is
// followed exactly rather than met by a bin of wrongly high density.
class Tabulated1D {
 public:
  Tabulated1D(const std::function<double(double)>& f, double lo, double hi, int bins = 1024)
      : lo_(lo), bin_width_((hi - lo) / bins), node_(bins + 1), cdf_(bins + 1, 0.0), guide_(bins) {
    for (int i = 0; i <= bins; ++i)
      node_[i] = std::abs(f(lo + i * bin_width_));
    for (int i = 0; i < bins; ++i)  // trapezoids: the exact mass of the linear pieces
      cdf_[i + 1] = cdf_[i] + 0.5 * (node_[i] + node_[i + 1]) * bin_width_;
    total_ = cdf_.back();
    for (double& c : cdf_)
      c /= total_;
    cdf_.back() = 1.0;
    // guide_[k]: the bin holding u = k / bins, where the search for any u in [k, k + 1) / bins
    // can start: about one step on average instead of a binary search's ten mispredicted
    // branches, which made sampling cost several times a filter evaluation.
    for (int k = 0, i = 0; k < bins; ++k) {
      while (i < bins - 1 && cdf_[i + 1] <= double(k) / bins)
        ++i;
      guide_[k] = i;
    }
  }

  struct Sample {
    double x;
    double pdf;  // never 0: at a zero of |f| (probability 0) it is 1, so f / pdf is 0, not NaN
  };

  Sample sample(double u) const {
    const int bins = static_cast<int>(guide_.size());
    int i = guide_[std::clamp(static_cast<int>(u * bins), 0, bins - 1)];
    while (i < bins - 1 && cdf_[i + 1] <= u)  // the bin with cdf[i] <= u < cdf[i + 1]
      ++i;
    const double mass = cdf_[i + 1] - cdf_[i];
    const double v = mass > 0.0 ? std::clamp((u - cdf_[i]) / mass, 0.0, 1.0) : 0.5;
    // Inverse CDF of the density a (1 - t) + b t on the bin, t in [0, 1]: the root of
    // a t + (b - a) t^2 / 2 = v (a + b) / 2, written without cancellation when a is close to b.
    const double a = node_[i], b = node_[i + 1];
    const double t = a + b > 0.0 ? v * (a + b) / (a + std::sqrt((1 - v) * a * a + v * b * b)) : v;
    const double density = (a + (b - a) * t) / total_;
    return {lo_ + (i + t) * bin_width_, density > 0.0 ? density : 1.0};
  }

 private:
  double lo_, bin_width_, total_;
  std::vector<double> node_;  // |f| at the nodes
  std::vector<double> cdf_;   // at the nodes, normalised
  std::vector<int> guide_;
};

}  // namespace fb
