// Filter `triangle` (tent): h(x, y) = t(x) t(y) with t(x) = max(0, r - |x|) / r^2, which
// integrates to 1. Each axis is sampled exactly by the tent's inverse CDF, so every weight is 1.
// The default radius, 1 px, is the kernel of linear interpolation (box * box): its response
// sinc^2(f r) is 0.41 at Nyquist, about the default Gaussian's blur; pbrt's default, 2 px, already
// falls to zero at Nyquist and blurs accordingly (docs/filters.md).
#include <filmback/plugin_sdk.h>

#include <cmath>

namespace {

constexpr fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "1", "px", nullptr, 1e-3, 16,
     "half-width of the support; 1 is linear interpolation's kernel"},
};
constexpr auto kRadius = fb::param<double>(kParams, "radius");

class Triangle {
 public:
  explicit Triangle(const fb_value* values) : radius_(kRadius(values)) {}
  float radius() const { return float(radius_); }
  float evaluate(float x, float y) const { return float(tent(x) * tent(y)); }
  double integral() const { return 1.0; }
  fb_filter_sample sample(float ux, float uy) const {
    return {float(inverse_cdf(ux)), float(inverse_cdf(uy)), 1.f};
  }

 private:
  double tent(double x) const {
    return std::abs(x) < radius_ ? (radius_ - std::abs(x)) / (radius_ * radius_) : 0.0;
  }
  // CDF(x) = (1 + x/r)^2 / 2 on [-r, 0] and 1 - (1 - x/r)^2 / 2 on [0, r], inverted.
  double inverse_cdf(double u) const {
    return u < 0.5 ? radius_ * (std::sqrt(2 * u) - 1) : radius_ * (1 - std::sqrt(2 - 2 * u));
  }
  double radius_;
};

constexpr fb_filter_api kApi = fb::filter_api<Triangle>();
constexpr fb_plugin kPlugin = fb::describe(
    "triangle", "1.0.0", "Triangle (tent) filter, normalised, sampled exactly by its inverse CDF",
    kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
