// Filter `blackman_harris`: Cycles' default pixel filter. Cycles' `width` (1.5 px by default) is
// the support's half-width: its filter_table() doubles the width before evaluating the 4-term
// Blackman-Harris window (Harris 1978, "On the use of windows for harmonic analysis with the
// discrete Fourier transform", table 1; -92 dB side lobes)
//   b(v) = 0.35875 - 0.48829 cos(2 pi s) + 0.14128 cos(4 pi s) - 0.01168 cos(6 pi s),
//   s = v / (2 w) + 1/2, for v in [-w, w]
// (Blender's intern/cycles/scene/film.cpp, filter_func_blackman_harris and filter_table's
// `width *= 2`; docs/filters.md). The cosines integrate to zero over s in [0, 1], so
// N = integral of b = 2 w 0.35875 in closed form, and h(x, y) = b(x) b(y) / N^2 integrates to 1.
// b is positive on its support; like Cycles, each axis is importance-sampled from one 1-D table,
// so the weight h / pdf is 1 up to the table's resolution.
#include <filmback/plugin_sdk.h>
#include <filmback/separable_filter.h>

#include <cmath>
#include <numbers>

namespace {

constexpr double kA0 = 0.35875, kA1 = 0.48829, kA2 = 0.14128, kA3 = 0.01168;

constexpr fb_param_desc kParams[] = {
    {"width", FB_PARAM_FLOAT, "1.5", "px", nullptr, 1e-3, 16,
     "Cycles' filter width: the support is +-width px (Cycles doubles it for this filter)"},
};
constexpr auto kWidth = fb::param<double>(kParams, "width");

class BlackmanHarris : public fb::SeparableFilter {
 public:
  explicit BlackmanHarris(const fb_value* values)
      : SeparableFilter(
            [width = kWidth(values)](double v) {
              if (std::abs(v) > width) return 0.0;
              // cos 2t = 2c^2 - 1 and cos 3t = (4c^2 - 3) c: one cosine instead of three.
              const double c = std::cos(2 * std::numbers::pi * (v / (2 * width) + 0.5));
              return kA0 - kA1 * c + kA2 * (2 * c * c - 1) - kA3 * (4 * c * c - 3) * c;
            },
            kWidth(values), 2 * kWidth(values) * kA0) {}
};

constexpr fb_filter_api kApi = fb::filter_api<BlackmanHarris>();
constexpr fb_plugin kPlugin = fb::describe("blackman_harris", "1.0.0",
                                           "Blackman-Harris filter as Cycles' default, normalised, "
                                           "importance-sampled",
                                           kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
