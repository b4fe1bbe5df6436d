// Filter `mitchell`: the cubic family of Mitchell & Netravali, "Reconstruction Filters in Computer
// Graphics" (SIGGRAPH 1988), with parameters B and C: k(x) is a piecewise cubic on
// |x| < 2 that sums to 1 over integer shifts for every B, C, so its integral is 1. The filter
// stretches it to radius r: h(x, y) = m(x) m(y) with m(x) = k(2x / r) / (r / 2), normalised in
// closed form. B = C = 1/3 is the paper's recommendation (its "satisfactory" region, B + 2C = 1),
// and r = 2 px puts k on its native 1-px grid, as pbrt does. Negative lobes (for C > 0) are
// importance-sampled through a table of |m|; their samples carry negative weights.
#include <filmback/plugin_sdk.h>
#include <filmback/separable_filter.h>

#include <cmath>

namespace {

fb::SeparableFilter make_mitchell(double radius_px, double b, double c) {
  auto k = [=](double x) {
    x = std::abs(x);
    if (x < 1)
      return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6;
    if (x < 2)
      return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x +
              (8 * b + 24 * c)) /
             6;
    return 0.0;
  };
  return fb::SeparableFilter([=](double x) { return k(2 * x / radius_px); }, radius_px,
                             radius_px / 2);
}

constexpr fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "2", "px", nullptr, 1e-3, 16,
     "half-width of the support; 2 keeps the cubic on its native 1-px knots"},
    {"b", FB_PARAM_FLOAT, "0.3333333333333333", "", nullptr, 0, 1,
     "Mitchell-Netravali B: blur (1 with C = 0 is the cubic B-spline)"},
    {"c", FB_PARAM_FLOAT, "0.3333333333333333", "", nullptr, 0, 1,
     "Mitchell-Netravali C: ringing, negative lobes (0.5 with B = 0 is Catmull-Rom)"},
};
constexpr auto kRadius = fb::param<double>(kParams, "radius");
constexpr auto kB = fb::param<double>(kParams, "b");
constexpr auto kC = fb::param<double>(kParams, "c");

class Mitchell : public fb::SeparableFilter {
 public:
  explicit Mitchell(const fb_value* values)
      : SeparableFilter(make_mitchell(kRadius(values), kB(values), kC(values))) {}
};

constexpr fb_filter_api kApi = fb::filter_api<Mitchell>();
constexpr fb_plugin kPlugin =
    fb::describe("mitchell", "1.0.0",
                 "Mitchell-Netravali cubic filter, normalised, importance-sampled "
                 "through a table of |h| (negative lobes keep their sign)",
                 kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
