/* Filter `frozenbox`, built against the frozen header: a box of half-width `radius` px (at most
 * half a pixel, so that every sample stays in its own pixel), sampled exactly. */
#include "filmback/plugin_abi.h"

#include <stdlib.h>

static const fb_param_desc params[] = {
    {"radius", FB_PARAM_FLOAT, "0.5", "px", NULL, 1e-3, 0.5, "half-width of the box per axis"},
};

static int create(const fb_value* values, void** instance, fb_error_buffer error) {
  float* radius_px = malloc(sizeof *radius_px);
  (void)error;
  if (!radius_px) return 1;
  *radius_px = (float)values[0].number[0];
  *instance = radius_px;
  return 0;
}

static void destroy(void* instance) {
  free(instance);
}

static void radius(const void* instance, float radius_px[2]) {
  radius_px[0] = radius_px[1] = *(const float*)instance;
}

static float evaluate(const void* instance, float x, float y) {
  const float r = *(const float*)instance;
  return x >= -r && x < r && y >= -r && y < r ? 1.f / (4.f * r * r) : 0.f;
}

static double integral(const void* instance) {
  (void)instance;
  return 1.0;
}

static void sample(const void* instance, const float* u, size_t count, fb_filter_sample* samples) {
  const float r = *(const float*)instance;
  size_t i;
  for (i = 0; i < count; ++i) {
    samples[i].x = r * (2.f * u[2 * i] - 1.f);
    samples[i].y = r * (2.f * u[2 * i + 1] - 1.f);
    samples[i].weight = 1.f;
  }
}

static const fb_filter_api api = {
    sizeof(fb_filter_api), create, destroy, radius, evaluate, integral, sample};

static const fb_plugin plugin = {FB_ABI_VERSION,
                                 sizeof(fb_plugin),
                                 FB_KIND_FILTER,
                                 "frozenbox",
                                 "1.0.0",
                                 "Box filter, built against the frozen header",
                                 params,
                                 1,
                                 &api};

FB_EXPORT const fb_plugin* filmback_plugin_v1(void) {
  return &plugin;
}
