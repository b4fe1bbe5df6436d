// Camera `outoftree`: a pinhole rolled about its view axis by `roll_deg`, built against the
// installed SDK only (tests/plugin_abi/sdk_test.cmake). It shows that a camera model with a
// parameter of its own needs no change in filmback: the schema below is all the host learns of it
// (`filmback plugins` lists it; `--camera-model outoftree:roll_deg=90` sets it). At roll 0 its
// rays are the perspective camera's, bit for bit, which the test checks on the rendered image.
#include <filmback/camera_projection.h>
#include <filmback/plugin_sdk.h>

#include <cmath>
#include <numbers>

namespace {

constexpr fb_param_desc kParams[] = {
    {"roll_deg", FB_PARAM_FLOAT, "0", "deg", nullptr, -360, 360,
     "rotation of the image about the view axis, counter-clockwise"},
};
constexpr auto kRoll = fb::param<double>(kParams, "roll_deg");

class RolledPinhole {
 public:
  RolledPinhole(const fb_value* values, const fb_camera_setup& setup)
      : plane_(fb::view_plane(setup)),
        near_(setup.clip_near_m),
        far_(setup.clip_far_m),
        cos_(float(std::cos(kRoll(values) * std::numbers::pi / 180))),
        sin_(float(std::sin(kRoll(values) * std::numbers::pi / 180))) {
    if (setup.projection != FB_PROJECTION_PERSPECTIVE)
      throw std::invalid_argument("a rolled pinhole needs a perspective projection");
    if (const char* problem = fb::view_plane_problem(plane_, setup))
      throw std::invalid_argument(problem);
  }

  uint32_t needs() const { return 0; }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    const float px = float((s.film_x - plane_.cx) / plane_.fx);
    const float py = float(-(s.film_y - plane_.cy) / plane_.fy);
    const float x = cos_ * px - sin_ * py, y = sin_ * px + cos_ * py;
    const float inv_length = 1.f / std::sqrt(x * x + y * y + 1.f);
    ray.origin[0] = ray.origin[1] = ray.origin[2] = 0.f;
    ray.direction[0] = x * inv_length;
    ray.direction[1] = y * inv_length;
    ray.direction[2] = -inv_length;
    ray.t_min = float(near_ / inv_length);  // clipped by depth along the view axis
    ray.t_max = float(far_ / inv_length);
    ray.weight = 1.f;
  }

 private:
  fb::ViewPlane plane_;
  double near_, far_;
  float cos_, sin_;
};

constexpr fb_camera_api kApi = fb::camera_api<RolledPinhole>();
constexpr fb_plugin kPlugin =
    fb::describe("outoftree", "1.0.0", "Pinhole rolled about its view axis", kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
