// Camera `pov_fisheye`: POV-Ray 3.7's `fisheye` camera (tracepixel.cpp CreateCameraRay,
// FISHEYE_CAMERA; docs/camera-model.md "POV-Ray's projections").
//
// The image point (x0, y0) (pov_projection.h) becomes u = 2 x0 |right|, v = 2 y0 |up|: the circle
// u^2 + v^2 <= 1 is the fisheye's image (|right| = 1.33, |up| = 1 on a 4:3 image: a circle of
// the image's height), and beyond it POV-Ray traces no ray. The radius r = sqrt(u^2 + v^2) is the
// angle from the view axis in units of half the field of view, an equidistant fisheye:
// theta = r angle / 2, so the circle's edge sees angle / 2 off the axis (angle 360: straight back).
#include <filmback/plugin_sdk.h>

#include "../pov_projection/pov_projection.h"

namespace {

namespace pp = fb::pov_projection;

constexpr fb_param_desc kParams[] = {pp::kAngleParam, pp::kRightLengthParam, pp::kUpLengthParam};
constexpr auto kAngle = fb::param<double>(kParams, "angle_deg");
constexpr auto kRightLength = fb::param<double>(kParams, "right_length_m");
constexpr auto kUpLength = fb::param<double>(kParams, "up_length_m");

class PovFisheye {
 public:
  PovFisheye(const fb_value* values, const fb_camera_setup& setup)
      : image_(setup),
        half_angle_rad_(kAngle(values) * pp::kRadiansPerDegree / 2),
        right_(kRightLength(values)),
        up_(kUpLength(values)) {}

  uint32_t needs() const { return 0; }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    const pp::ImagePoint p = image_.point(s);
    const double u = 2 * p.x0 * right_, v = 2 * p.y0 * up_;
    const double r = std::sqrt(u * u + v * v);
    if (r > 1) return pp::PovImage::set_no_ray(ray);
    pp::set_polar_ray(image_, u, v, r, r * half_angle_rad_, ray);
  }

 private:
  pp::PovImage image_;
  double half_angle_rad_, right_, up_;
};

constexpr fb_camera_api kApi = fb::camera_api<PovFisheye>();
constexpr fb_plugin kPlugin =
    fb::describe("pov_fisheye", "1.0.0",
                 "POV-Ray's fisheye camera: equidistant, angle across the circle of |right| x |up|",
                 kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
