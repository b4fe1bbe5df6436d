/* Integrator `frozendepth`, built against the frozen header (filmback/plugin_abi.h beside this
 * file, the layout before issue 14): its hit records are shorter than this filmback's and it knows
 * a shorter fb_scene_api, so it renders only if the host writes hits with its stride and reads no
 * further (tests/sdk/abi_growth_test.cpp).
 *
 * R: depth along the view axis of the camera ray's hit, from intersect_batch (the stride);
 * G: distance t of the same ray traced alone by intersect();
 * B: the hit's base_color[0], a field behind both normals in the record.
 * Misses are 0. If the host hands it a scene or table of another size than it was built with, every
 * value is -1: the test then fails. */
#include "filmback/plugin_abi.h"

#include <math.h>
#include <stdlib.h>

static int create(const fb_value* params, void** instance, fb_error_buffer error) {
  (void)params;
  (void)error;
  *instance = malloc(1);
  return *instance ? 0 : 1;
}

static void destroy(void* instance) {
  free(instance);
}

static uint32_t channels(const void* instance, const char** names, uint32_t capacity) {
  static const char* const kNames[3] = {"R", "G", "B"};
  uint32_t i;
  (void)instance;
  for (i = 0; i < 3 && i < capacity; ++i)
    names[i] = kNames[i];
  return 3;
}

static void radiance(const void* instance, const fb_scene* scene, fb_trace_context* context,
                     const fb_ray* rays, size_t count, float* values) {
  fb_hit* hits = malloc(count * sizeof *hits);
  size_t i;
  int c;
  (void)instance;
  if (!hits || scene->struct_size != sizeof(fb_scene) ||
      scene->api->struct_size != sizeof(fb_scene_api)) {
    for (i = 0; i < 3 * count; ++i)
      values[i] = -1.f;
    free(hits);
    return;
  }
  scene->api->intersect_batch(context, rays, count, hits);
  for (i = 0; i < count; ++i) {
    float* v = values + 3 * i;
    fb_hit alone;
    v[0] = v[1] = v[2] = 0.f;
    if (isinf(hits[i].t)) continue;
    for (c = 0; c < 3; ++c)
      v[0] += hits[i].position[c] * scene->view_axis[c];
    if (scene->api->intersect(context, &rays[i], &alone)) v[1] = alone.t;
    v[2] = hits[i].base_color[0];
  }
  free(hits);
}

static const fb_integrator_api api = {
    sizeof(fb_integrator_api), create, destroy, channels, radiance, sizeof(fb_hit)};

static const fb_plugin plugin = {FB_ABI_VERSION,
                                 sizeof(fb_plugin),
                                 FB_KIND_INTEGRATOR,
                                 "frozendepth",
                                 "1.0.0",
                                 "Depth, distance and base colour, built against the frozen header",
                                 NULL,
                                 0,
                                 &api};

FB_EXPORT const fb_plugin* filmback_plugin_v1(void) {
  return &plugin;
}
