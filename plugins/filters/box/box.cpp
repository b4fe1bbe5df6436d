// Filter `box`: h(x, y) = 1 / (4 r^2) on [-r, r]^2, sampled exactly (every weight is 1).
// With r = 0.5 px each sample stays inside its pixel: the plain pixel average.
#include <filmback/plugin_sdk.h>

#include <cmath>

namespace {

constexpr fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "0.5", "px", nullptr, 1e-3, 16, "half-width of the square support"},
};
constexpr auto kRadius = fb::param<float>(kParams, "radius");

class Box {
 public:
  explicit Box(const fb_value* values) : radius_(kRadius(values)) {}
  float radius() const { return radius_; }
  float evaluate(float x, float y) const {
    const bool inside = std::abs(x) <= radius_ && std::abs(y) <= radius_;
    return inside ? 1.f / (4.f * radius_ * radius_) : 0.f;
  }
  double integral() const { return 1.0; }
  fb_filter_sample sample(float ux, float uy) const {
    return {(2.f * ux - 1.f) * radius_, (2.f * uy - 1.f) * radius_, 1.f};
  }

 private:
  float radius_;
};

constexpr fb_filter_api kApi = fb::filter_api<Box>();
constexpr fb_plugin kPlugin =
    fb::describe("box", "1.0.0", "Box filter, normalised, sampled exactly", kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
