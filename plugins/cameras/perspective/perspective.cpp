// Camera `perspective`: a pinhole. Rays leave the camera origin through the view plane that
// Blender's sensor, focal length, fit and shift define (filmback/camera_projection.h); clipping
// is by depth along the view axis, as in Blender. No lens samples, no time samples, weight 1.
#include <filmback/camera_projection.h>
#include <filmback/plugin_sdk.h>

#include <cmath>

namespace {

class Perspective {
 public:
  explicit Perspective(const fb_camera_setup& setup)
      : plane_(fb::view_plane(setup)), near_(setup.clip_near_m), far_(setup.clip_far_m) {}

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    const float x = float((s.film_x - plane_.cx) / plane_.fx);
    const float y = float(-(s.film_y - plane_.cy) / plane_.fy);
    const float inv_length = 1.f / std::sqrt(x * x + y * y + 1.f);
    ray.origin[0] = ray.origin[1] = ray.origin[2] = 0.f;
    ray.direction[0] = x * inv_length;
    ray.direction[1] = y * inv_length;
    ray.direction[2] = -inv_length;
    // depth = t * cos(theta), with cos(theta) = inv_length
    ray.t_min = float(near_ / inv_length);
    ray.t_max = float(far_ / inv_length);
    ray.weight = 1.f;
  }

 private:
  fb::ViewPlane plane_;
  double near_, far_;
};

int create(const fb_value*, const fb_camera_setup* setup, void** instance, fb_error_buffer error) {
  if (setup->projection != FB_PROJECTION_PERSPECTIVE)
    return fb::fail(error, "the shot's camera is not a perspective one (use the orthographic camera)");
  if (!(setup->focal_length_mm > 0) || !(setup->sensor_width_mm > 0) || !(setup->sensor_height_mm > 0))
    return fb::fail(error, "focal length %g mm and sensor %g x %g mm must be positive",
                    setup->focal_length_mm, setup->sensor_width_mm, setup->sensor_height_mm);
  if (!(setup->clip_near_m >= 0) || !(setup->clip_far_m > setup->clip_near_m))
    return fb::fail(error, "clip range [%g, %g] m is empty", setup->clip_near_m, setup->clip_far_m);
  return fb::create_instance<Perspective>(instance, error, *setup);
}

uint32_t needs(const void*) { return 0; }

void generate_rays(const void* self, const fb_camera_sample* samples, size_t count,
                   fb_camera_ray* rays) {
  const auto& camera = *static_cast<const Perspective*>(self);
  for (size_t i = 0; i < count; ++i) camera.generate(samples[i], rays[i]);
}

const fb_camera_api kApi = {sizeof(fb_camera_api), create, fb::destroy_instance<Perspective>,
                            needs, generate_rays};

const fb_plugin kPlugin = {FB_ABI_VERSION, sizeof(fb_plugin), FB_KIND_CAMERA, "perspective", "1.0.0",
                           "Pinhole camera with Blender's sensor, focal length, sensor fit and lens shift",
                           nullptr, 0, &kApi};

}  // namespace

extern "C" FB_EXPORT const fb_plugin* filmback_plugin_v1(void) { return &kPlugin; }
