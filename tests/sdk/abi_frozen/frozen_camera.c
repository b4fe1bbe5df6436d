/* Camera `frozenpinhole`, built against the frozen header: a pinhole that reads the image size,
 * focal length and sensor width from the fb_camera_setup it was built with (the host's is longer),
 * with the sensor fitted horizontally. Every ray goes through its pixel's centre, so a pixel's
 * value does not depend on where the filter put the sample inside it. */
#include "filmback/plugin_abi.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct pinhole {
  float width_px, height_px;
  float half_width; /* tan of half the horizontal field of view: sensor width / (2 focal) */
} pinhole;

static int create(const fb_value* params, const fb_camera_setup* setup, void** instance,
                  fb_error_buffer error) {
  pinhole* self;
  (void)params;
  if (setup->projection != FB_PROJECTION_PERSPECTIVE || !(setup->focal_length_mm > 0)) {
    snprintf(error.text, error.capacity, "frozenpinhole needs a perspective camera");
    return 1;
  }
  self = malloc(sizeof *self);
  if (!self) return 1;
  self->width_px = (float)setup->image_width_px;
  self->height_px = (float)setup->image_height_px;
  self->half_width = (float)(setup->sensor_width_mm / (2 * setup->focal_length_mm));
  *instance = self;
  return 0;
}

static void destroy(void* instance) {
  free(instance);
}

static uint32_t needs(const void* instance) {
  (void)instance;
  return 0;
}

static void generate_rays(const void* instance, const fb_camera_sample* samples, size_t count,
                          fb_camera_ray* rays) {
  const pinhole* self = instance;
  size_t i;
  for (i = 0; i < count; ++i) {
    /* the pixel's centre, in [-1, 1] across the width; y up, scaled by the same half width */
    const float x = (2.f * (floorf(samples[i].film_x) + 0.5f) / self->width_px - 1.f);
    const float y = (1.f - 2.f * (floorf(samples[i].film_y) + 0.5f) / self->height_px) *
                    self->height_px / self->width_px;
    const float d[3] = {x * self->half_width, y * self->half_width, -1.f};
    const float length = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    fb_camera_ray* r = &rays[i];
    r->origin[0] = r->origin[1] = r->origin[2] = 0.f;
    r->direction[0] = d[0] / length;
    r->direction[1] = d[1] / length;
    r->direction[2] = d[2] / length;
    r->t_min = 0.f;
    r->t_max = INFINITY;
    r->weight = 1.f;
  }
}

static const fb_camera_api api = {sizeof(fb_camera_api), create, destroy, needs, generate_rays};

static const fb_plugin plugin = {FB_ABI_VERSION,
                                 sizeof(fb_plugin),
                                 FB_KIND_CAMERA,
                                 "frozenpinhole",
                                 "1.0.0",
                                 "Pinhole through pixel centres, built against the frozen header",
                                 NULL,
                                 0,
                                 &api};

FB_EXPORT const fb_plugin* filmback_plugin_v1(void) {
  return &plugin;
}
