// Filter `lanczos`: the windowed sinc l(x) = sinc(x) sinc(x / tau) on |x| < r, sinc(x) =
// sin(pi x) / (pi x) (pbrt 4e's LanczosSincFilter), and h(x, y) = l(x) l(y) / N^2 with N
// = integral of l found by Simpson's rule, so h integrates to 1. sinc(x) is the ideal low-pass
// filter for a 1-px sampling grid; the window tames its slow decay.
//
// Defaults r = tau = 3 (Lanczos-3, Turkowski 1990; Mitsuba's `lanczos` default): the window ends
// at its own first zero, so l is continuous and every lobe keeps the sign of the sinc it
// approximates. pbrt's default, r = 4 with tau = 3, runs the window past its first zero, where it
// turns negative and flips the sinc's fourth lobe positive.
//
// Negative lobes are importance-sampled through a table of |h|; their samples carry negative
// weights.
#include <filmback/plugin_sdk.h>
#include <filmback/separable_filter.h>

#include <cmath>
#include <numbers>

namespace {

double sinc(double x) {
  const double px = std::numbers::pi * x;
  return std::abs(px) < 1e-6 ? 1 - px * px / 6 : std::sin(px) / px;
}

constexpr fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "3", "px", nullptr, 0.5, 16, "half-width of the support"},
    {"tau", FB_PARAM_FLOAT, "3", "px", nullptr, 1, 16,
     "the window sinc(x/tau) reaches its first zero at tau px; tau = radius is Lanczos' window"},
};
constexpr auto kRadius = fb::param<double>(kParams, "radius");
constexpr auto kTau = fb::param<double>(kParams, "tau");

class Lanczos : public fb::SeparableFilter {
 public:
  explicit Lanczos(const fb_value* values)
      : SeparableFilter(
            [radius = kRadius(values), tau = kTau(values)](double x) {
              return std::abs(x) < radius ? sinc(x) * sinc(x / tau) : 0.0;
            },
            kRadius(values)) {}
};

constexpr fb_filter_api kApi = fb::filter_api<Lanczos>();
constexpr fb_plugin kPlugin =
    fb::describe("lanczos", "1.0.0",
                 "Lanczos windowed-sinc filter, normalised, importance-sampled through "
                 "a table of |h| (negative lobes keep their sign)",
                 kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
