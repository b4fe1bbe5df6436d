// Filter `gaussian`: h(x, y) = g(x) g(y) / N^2 with g(x) = exp(-x^2 / 2 sigma^2) - exp(-r^2 / 2
// sigma^2) on |x| < r, so h falls continuously to zero at the radius (pbrt 4e §8.8.2), and N =
// integral of g = sigma sqrt(2 pi) erf(r / (sigma sqrt 2)) - 2 r exp(-r^2 / 2 sigma^2), so h
// integrates to 1. Positions are importance-sampled per axis from a table of g
// (fb::SeparableFilter); the weight h / pdf is then 1 up to the table's resolution.
#include <filmback/plugin_sdk.h>
#include <filmback/separable_filter.h>

#include <cmath>
#include <numbers>

namespace {

fb::SeparableFilter make_gaussian(double radius_px, double sigma_px) {
  const double floor = std::exp(-radius_px * radius_px / (2 * sigma_px * sigma_px));
  const double norm = sigma_px * std::sqrt(2 * std::numbers::pi) *
                          std::erf(radius_px / (sigma_px * std::numbers::sqrt2)) -
                      2 * radius_px * floor;
  return fb::SeparableFilter(
      [=](double x) {
        return std::abs(x) < radius_px ? std::exp(-x * x / (2 * sigma_px * sigma_px)) - floor : 0.0;
      },
      radius_px, norm);
}

constexpr fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "1.5", "px", nullptr, 1e-3, 16, "support half-width; zero beyond"},
    {"sigma", FB_PARAM_FLOAT, "0.5", "px", nullptr, 1e-3, 16, "standard deviation"},
};
constexpr auto kRadius = fb::param<double>(kParams, "radius");
constexpr auto kSigma = fb::param<double>(kParams, "sigma");

class Gaussian : public fb::SeparableFilter {
 public:
  explicit Gaussian(const fb_value* values)
      : SeparableFilter(make_gaussian(kRadius(values), kSigma(values))) {}
};

constexpr fb_filter_api kApi = fb::filter_api<Gaussian>();
constexpr fb_plugin kPlugin =
    fb::describe("gaussian", "1.0.0",
                 "Gaussian filter, shifted to reach zero at its radius, normalised, "
                 "importance-sampled",
                 kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
