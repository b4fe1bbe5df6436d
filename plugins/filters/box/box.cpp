// Filter `box`: h(x, y) = 1 / (4 r^2) on [-r, r]^2, sampled exactly (every weight is 1).
// With r = 0.5 px each sample stays inside its pixel: the plain pixel average.
#include <filmback/plugin_sdk.h>

#include <cmath>

namespace {

class Box {
 public:
  explicit Box(double radius_px) : radius_(float(radius_px)) {}
  float radius() const { return radius_; }
  float evaluate(float x, float y) const {
    const bool inside = std::abs(x) <= radius_ && std::abs(y) <= radius_;
    return inside ? 1.f / (4.f * radius_ * radius_) : 0.f;
  }
  fb_filter_sample sample(float ux, float uy) const {
    return {(2.f * ux - 1.f) * radius_, (2.f * uy - 1.f) * radius_, 1.f};
  }

 private:
  float radius_;
};

const fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "0.5", "px", nullptr, 1e-3, 16, "half-width of the square support"},
};

int create(const fb_value* params, void** instance, fb_error_buffer error) {
  return fb::create_instance<Box>(instance, error, params[0].number[0]);
}
void radius(const void* self, float r[2]) { r[0] = r[1] = static_cast<const Box*>(self)->radius(); }
float evaluate(const void* self, float x, float y) { return static_cast<const Box*>(self)->evaluate(x, y); }
double integral(const void*) { return 1.0; }
void sample(const void* self, const float* u, size_t count, fb_filter_sample* out) {
  const auto& box = *static_cast<const Box*>(self);
  for (size_t i = 0; i < count; ++i) out[i] = box.sample(u[2 * i], u[2 * i + 1]);
}

const fb_filter_api kApi = {sizeof(fb_filter_api), create, fb::destroy_instance<Box>, radius,
                            evaluate, integral, sample};

const fb_plugin kPlugin = {FB_ABI_VERSION, sizeof(fb_plugin), FB_KIND_FILTER, "box", "1.0.0",
                           "Box filter, normalised, sampled exactly", kParams,
                           sizeof kParams / sizeof kParams[0], &kApi};

}  // namespace

extern "C" FB_EXPORT const fb_plugin* filmback_plugin_v1(void) { return &kPlugin; }
