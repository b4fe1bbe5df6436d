// Filter `gaussian`: h(x, y) = g(x) g(y) / N^2 with g(x) = exp(-x^2 / 2 sigma^2) - exp(-r^2 / 2
// sigma^2) on |x| < r, so h falls continuously to zero at the radius (pbrt 4e §8.8.2), and N =
// integral of g = sigma sqrt(2 pi) erf(r / (sigma sqrt 2)) - 2 r exp(-r^2 / 2 sigma^2), so h
// integrates to 1. Positions are importance-sampled per axis from a 1024-bin table of g; the weight
// h / pdf is then 1 up to the table's resolution.
#include <filmback/plugin_sdk.h>
#include <filmback/sampling.h>

#include <cmath>
#include <numbers>

namespace {

class Gaussian {
 public:
  explicit Gaussian(const fb_value* params) : Gaussian(params[0].number[0], params[1].number[0]) {}
  Gaussian(double radius_px, double sigma_px)
      : radius_(radius_px),
        sigma_(sigma_px),
        floor_(std::exp(-radius_px * radius_px / (2 * sigma_px * sigma_px))),
        norm_(sigma_px * std::sqrt(2 * std::numbers::pi) *
                  std::erf(radius_px / (sigma_px * std::numbers::sqrt2)) -
              2 * radius_px * floor_),
        table_([this](double x) { return g(x); }, -radius_px, radius_px) {}

  double g(double x) const {
    return std::abs(x) < radius_ ? std::exp(-x * x / (2 * sigma_ * sigma_)) - floor_ : 0.0;
  }
  float radius() const { return float(radius_); }
  float evaluate(float x, float y) const { return float(g(x) * g(y) / (norm_ * norm_)); }
  double integral() const { return 1.0; }
  fb_filter_sample sample(float ux, float uy) const {
    const fb::Tabulated1D::Sample sx = table_.sample(ux), sy = table_.sample(uy);
    const double weight = g(sx.x) * g(sy.x) / (norm_ * norm_ * sx.pdf * sy.pdf);
    return {float(sx.x), float(sy.x), float(weight)};
  }

 private:
  double radius_, sigma_, floor_, norm_;
  fb::Tabulated1D table_;
};

const fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "1.5", "px", nullptr, 1e-3, 16, "support half-width; zero beyond"},
    {"sigma", FB_PARAM_FLOAT, "0.5", "px", nullptr, 1e-3, 16, "standard deviation"},
};

constexpr fb_filter_api kApi = fb::filter_api<Gaussian>();
const fb_plugin kPlugin = {FB_ABI_VERSION,
                           sizeof(fb_plugin),
                           FB_KIND_FILTER,
                           "gaussian",
                           "1.0.0",
                           "Gaussian filter, shifted to reach zero at its radius, normalised, "
                           "importance-sampled",
                           kParams,
                           sizeof kParams / sizeof kParams[0],
                           &kApi};

}  // namespace

extern "C" FB_EXPORT const fb_plugin* filmback_plugin_v1(void) {
  return &kPlugin;
}
