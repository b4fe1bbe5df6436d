/* Integrator `future`, built against this filmback's header but claiming the records of a newer
 * one: a hit_size larger than this host's fb_hit. The loader must refuse it, naming the file and
 * both sizes (tests/sdk/abi_growth_test.cpp); it never runs. */
#include <filmback/plugin_abi.h>

#include <stddef.h>

static int create(const fb_value* params, void** instance, fb_error_buffer error) {
  (void)params;
  (void)error;
  *instance = NULL;
  return 1;
}

static void destroy(void* instance) {
  (void)instance;
}

static uint32_t channels(const void* instance, const char** names, uint32_t capacity) {
  (void)instance;
  (void)names;
  (void)capacity;
  return 0;
}

static void radiance(const void* instance, const fb_scene* scene, fb_trace_context* context,
                     const fb_ray* rays, size_t count, float* values) {
  (void)instance, (void)scene, (void)context, (void)rays, (void)count, (void)values;
}

/* A newer header that appended four floats to fb_hit. */
static const fb_integrator_api api = {sizeof(fb_integrator_api),
                                      create,
                                      destroy,
                                      channels,
                                      radiance,
                                      sizeof(fb_hit) + 4 * sizeof(float),
                                      sizeof(fb_scene),
                                      sizeof(fb_scene_api)};

static const fb_plugin plugin = {FB_ABI_VERSION,
                                 sizeof(fb_plugin),
                                 FB_KIND_INTEGRATOR,
                                 "future",
                                 "1.0.0",
                                 "An integrator from a newer SDK",
                                 NULL,
                                 0,
                                 &api};

FB_EXPORT const fb_plugin* filmback_plugin_v1(void) {
  return &plugin;
}
