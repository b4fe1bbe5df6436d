// Filter `outoftree`: a box of adjustable radius, the smallest complete plugin built against the
// installed SDK (tests/plugin_abi/sdk_test.cmake). h(x, y) = 1 / (4 r^2) on [-r, r]^2, sampled
// exactly, so every weight is 1.
#include <filmback/plugin_sdk.h>

#include <cmath>

namespace {

struct Box {
  float radius_px;
};

constexpr fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "0.5", "px", nullptr, 1e-3, 16, "half-width of the square support"},
};
constexpr auto kRadius = fb::param<float>(kParams, "radius");  // by name, not by position

int create(const fb_value* values, void** instance, fb_error_buffer error) {
  return fb::create_instance<Box>(instance, error, Box{kRadius(values)});
}
void radius(const void* self, float r[2]) {
  r[0] = r[1] = static_cast<const Box*>(self)->radius_px;
}
float evaluate(const void* self, float x, float y) {
  const float r = static_cast<const Box*>(self)->radius_px;
  return std::abs(x) <= r && std::abs(y) <= r ? 1.f / (4.f * r * r) : 0.f;
}
double integral(const void*) {
  return 1.0;
}
void sample(const void* self, const float* u, size_t count, fb_filter_sample* out) {
  const float r = static_cast<const Box*>(self)->radius_px;
  for (size_t i = 0; i < count; ++i)
    out[i] = {(2.f * u[2 * i] - 1.f) * r, (2.f * u[2 * i + 1] - 1.f) * r, 1.f};
}

const fb_filter_api kApi = {
    sizeof(fb_filter_api), create, fb::destroy_instance<Box>, radius, evaluate, integral, sample};

constexpr fb_plugin kPlugin = fb::describe(
    "outoftree", "1.0.0", "Box filter built out of tree against the installed SDK", kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
