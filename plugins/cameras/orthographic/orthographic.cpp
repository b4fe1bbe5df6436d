// Camera `orthographic`: parallel rays along -Z from the view plane, whose extent along the
// fitted side is Blender's ortho scale (glTF: 2 * max(xmag, ymag)); shift as for perspective.
#include <filmback/camera_projection.h>
#include <filmback/plugin_sdk.h>

namespace {

class Orthographic {
 public:
  Orthographic(const fb_value*, const fb_camera_setup& setup)
      : plane_(fb::view_plane(setup)), near_(setup.clip_near_m), far_(setup.clip_far_m) {
    if (setup.projection != FB_PROJECTION_ORTHOGRAPHIC)
      throw std::invalid_argument(
          "the shot's camera is not an orthographic one (use the perspective camera)");
    if (!(setup.ortho_scale_m > 0)) throw std::invalid_argument("the ortho scale must be positive");
    if (!(far_ > near_)) throw std::invalid_argument("the clip range is empty");
    if (const char* problem = fb::view_plane_problem(plane_, setup))
      throw std::invalid_argument(problem);
    if (setup.sensor_model == FB_SENSOR_PHYSICAL)
      throw std::invalid_argument(
          "the physical sensor needs an aperture to expose through (use thinlens)");
  }

  uint32_t needs() const { return 0; }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    ray.origin[0] = float((s.film_x - plane_.cx) / plane_.fx);
    ray.origin[1] = float(-(s.film_y - plane_.cy) / plane_.fy);
    ray.origin[2] = 0.f;
    ray.direction[0] = ray.direction[1] = 0.f;
    ray.direction[2] = -1.f;
    ray.t_min = float(near_);
    ray.t_max = float(far_);
    ray.weight = 1.f;
  }

 private:
  fb::ViewPlane plane_;
  double near_, far_;
};

constexpr fb_camera_api kApi = fb::camera_api<Orthographic>();
constexpr fb_plugin kPlugin =
    fb::describe("orthographic", "1.0.0",
                 "Parallel projection with Blender's ortho scale, sensor fit and lens shift", kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
