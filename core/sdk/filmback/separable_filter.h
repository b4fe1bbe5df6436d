// The common body of separable pixel filters without an analytic inverse CDF: h(x, y) = g(x) g(y)
// / N^2 on [-r, r]^2 with N = integral of g, so h integrates to 1 (as box and gaussian do), and
// offsets importance-sampled per axis from a Tabulated1D of |g| (pbrt 4e's FilterSampler does the
// same from a 2-D table of constant pieces). The weight h / pdf keeps the sign of h, so negative
// lobes subtract. A plugin supplies g, its radius and, where it has one, the closed form of N.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "plugin_abi.h"
#include "sampling.h"

namespace fb {

// Composite Simpson rule with `intervals` (even) panels: for the filters' smooth g, 2^14 panels
// put the error far below float precision.
inline double integrate_simpson(const std::function<double(double)>& f, double lo, double hi,
                                int intervals = 1 << 14) {
  const double h = (hi - lo) / intervals;
  double sum = f(lo) + f(hi);
  for (int i = 1; i < intervals; ++i)
    sum += (i % 2 ? 4.0 : 2.0) * f(lo + i * h);
  return sum * h / 3.0;
}

class SeparableFilter {
 public:
  // g must vanish beyond radius_px; without integral_of_g, N is found by Simpson's rule.
  SeparableFilter(std::function<double(double)> g, double radius_px,
                  std::optional<double> integral_of_g = std::nullopt)
      : g_(std::move(g)),
        radius_(radius_px),
        norm_(integral_of_g ? *integral_of_g : integrate_simpson(g_, -radius_px, radius_px)),
        table_(g_, -radius_px, radius_px, bins(radius_px)) {
    if (!(norm_ > 0))
      throw std::invalid_argument("the filter's integral is " + std::to_string(norm_) +
                                  ", expected a positive value");
  }

  // 512 table pieces per pixel: for radii that are multiples of 1/512 px the nodes fall on every
  // whole pixel, where sinc-like filters cross zero, so |g| is followed exactly there too.
  static int bins(double radius_px) { return std::max(64, int(std::ceil(2 * radius_px * 512))); }

  float radius() const { return float(radius_); }
  // The normalised 1-D profile g(x) / N.
  double profile(double x) const { return std::abs(x) <= radius_ ? g_(x) / norm_ : 0.0; }
  float evaluate(float x, float y) const { return float(profile(x) * profile(y)); }
  double integral() const { return 1.0; }
  fb_filter_sample sample(float ux, float uy) const {
    const Tabulated1D::Sample sx = table_.sample(ux), sy = table_.sample(uy);
    const double weight = profile(sx.x) * profile(sy.x) / (sx.pdf * sy.pdf);
    return {float(sx.x), float(sy.x), float(weight)};
  }

 private:
  std::function<double(double)> g_;
  double radius_, norm_;
  Tabulated1D table_;
};

}  // namespace fb
