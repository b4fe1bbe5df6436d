/* Filter `ctent`, written in plain C99 and compiled as C: the plugin ABI needs no C++ on the
 * plugin's side (tests/plugin_abi/loader_errors_test.cpp loads it and checks its values).
 *
 * h(x, y) = t(x) t(y) with t(x) = (1 - |x|/r) / r on [-r, r], so h integrates to 1. It is sampled
 * exactly by inverting the CDF of t, F(x) = (x + r)^2 / (2 r^2) for x <= 0 and
 * 1 - (r - x)^2 / (2 r^2) for x >= 0, so every sample weight is 1. */
#include <filmback/plugin_abi.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct tent {
  float radius_px;
} tent;

static const fb_param_desc params[] = {
    {"radius", FB_PARAM_FLOAT, "1", "px", NULL, 1e-3, 16, "half-width of the support per axis"},
};

static int create(const fb_value* values, void** instance, fb_error_buffer error) {
  tent* self = malloc(sizeof *self);
  if (!self) {
    snprintf(error.text, error.capacity, "out of memory");
    return 1;
  }
  self->radius_px = (float)values[0].number[0];
  *instance = self;
  return 0;
}

static void destroy(void* instance) {
  free(instance);
}

static void radius(const void* instance, float radius_px[2]) {
  radius_px[0] = radius_px[1] = ((const tent*)instance)->radius_px;
}

static float tent_1d(float x, float r) {
  const float distance = fabsf(x);
  return distance < r ? (1.f - distance / r) / r : 0.f;
}

static float evaluate(const void* instance, float x, float y) {
  const float r = ((const tent*)instance)->radius_px;
  return tent_1d(x, r) * tent_1d(y, r);
}

static double integral(const void* instance) {
  (void)instance;
  return 1.0;
}

static float sample_tent_1d(float u, float r) {
  return u < 0.5f ? r * (sqrtf(2.f * u) - 1.f) : r * (1.f - sqrtf(2.f - 2.f * u));
}

static void sample(const void* instance, const float* u, size_t count, fb_filter_sample* samples) {
  const float r = ((const tent*)instance)->radius_px;
  for (size_t i = 0; i < count; ++i) {
    samples[i].x = sample_tent_1d(u[2 * i], r);
    samples[i].y = sample_tent_1d(u[2 * i + 1], r);
    samples[i].weight = 1.f;
  }
}

static const fb_filter_api api = {
    sizeof(fb_filter_api), create, destroy, radius, evaluate, integral, sample};

static const fb_plugin plugin = {FB_ABI_VERSION,
                                 sizeof(fb_plugin),
                                 FB_KIND_FILTER,
                                 "ctent",
                                 "1.0.0",
                                 "Tent filter in plain C, sampled exactly",
                                 params,
                                 sizeof params / sizeof params[0],
                                 &api};

FB_EXPORT const fb_plugin* filmback_plugin_v1(void) {
  return &plugin;
}
