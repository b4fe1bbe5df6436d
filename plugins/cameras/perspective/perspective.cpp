// Camera `perspective`: a pinhole. Rays leave the camera origin through the view plane that
// Blender's sensor, focal length, fit and shift define (filmback/camera_projection.h); clipping
// is by depth along the view axis, as in Blender. No lens samples, no time samples, weight 1.
// A tracked clip's lens distortion (filmback/lens_distortion.h) moves each film position to the
// undistorted one before the projection; a position the model cannot undistort has weight 0.
#include <filmback/camera_projection.h>
#include <filmback/lens_distortion.h>
#include <filmback/plugin_sdk.h>

#include <cmath>

namespace {

constexpr fb_param_desc kParams[] = {FB_LENS_DISTORTION_PARAMS};

class Perspective {
 public:
  Perspective(const fb_value* values, const fb_camera_setup& setup)
      : plane_(fb::view_plane(setup)),
        near_(setup.clip_near_m),
        far_(setup.clip_far_m),
        distortion_(fb::lens_distortion_params(kParams, values)),
        width_px_(setup.image_width_px),
        height_px_(setup.image_height_px) {
    if (setup.projection != FB_PROJECTION_PERSPECTIVE)
      throw std::invalid_argument(
          "the shot's camera is not a perspective one (use the orthographic camera)");
    if (!(setup.focal_length_mm > 0) || !(setup.sensor_width_mm > 0) ||
        !(setup.sensor_height_mm > 0))
      throw std::invalid_argument("focal length and sensor size must be positive");
    if (!(near_ >= 0) || !(far_ > near_)) throw std::invalid_argument("the clip range is empty");
    if (const char* problem = fb::view_plane_problem(plane_, setup))
      throw std::invalid_argument(problem);
    if (setup.sensor_model == FB_SENSOR_PHYSICAL)
      throw std::invalid_argument(
          "the physical sensor needs an aperture to expose through (use thinlens)");
  }

  uint32_t needs() const { return 0; }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    fb::Vec2d film{s.film_x, s.film_y};
    ray.weight = 1.f;
    if (!distortion_.identity()) {
      const std::optional<fb::Vec2d> undistorted =
          distortion_.undistorted_film(film, width_px_, height_px_);
      if (undistorted)
        film = *undistorted;
      else
        ray.weight = 0.f;  // beyond the model's fold: black, along the undistorted ray
    }
    const float x = float((film.x - plane_.cx) / plane_.fx);
    const float y = float(-(film.y - plane_.cy) / plane_.fy);
    const float inv_length = 1.f / std::sqrt(x * x + y * y + 1.f);
    ray.origin[0] = ray.origin[1] = ray.origin[2] = 0.f;
    ray.direction[0] = x * inv_length;
    ray.direction[1] = y * inv_length;
    ray.direction[2] = -inv_length;
    // depth = t cos(theta), with cos(theta) = inv_length
    ray.t_min = float(near_ / inv_length);
    ray.t_max = float(far_ / inv_length);
  }

 private:
  fb::ViewPlane plane_;
  double near_, far_;
  fb::LensDistortion distortion_;
  double width_px_, height_px_;
};

constexpr fb_camera_api kApi = fb::camera_api<Perspective>();
constexpr fb_plugin kPlugin = fb::describe(
    "perspective", "1.1.0",
    "Pinhole camera with Blender's sensor, focal length, sensor fit, lens shift and a tracked "
    "clip's lens distortion",
    kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
