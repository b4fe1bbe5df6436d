// Camera `pov_cylinder`: POV-Ray 3.7's `cylinder 1` to `cylinder 4` cameras (tracepixel.cpp
// CreateCameraRay, CYL_1_CAMERA to CYL_4_CAMERA; docs/camera-model.md "POV-Ray's projections").
//
// One image axis turns through `angle` around the cylinder's axis, the other runs along the axis
// with the length of its vector. With (x0, y0) the image point (pov_projection.h),
// a = x0 angle and b = y0 angle:
//   1: axis up, rays from the camera:     sin(a) right + y0 |up| up + cos(a) direction
//   2: axis right, rays from the camera:  x0 |right| right + sin(b) up + cos(b) direction
//   3: axis up, rays from location + y0 |up| up:        sin(a) right + cos(a) direction
//   4: axis right, rays from location + x0 |right| right: sin(b) up + cos(b) direction
// (right, up and direction normalised): 1 and 2 are the cylindrical panorama of a centre,
// 3 and 4 are orthographic along the axis.
#include <filmback/plugin_sdk.h>

#include "plugins/cameras/pov_projection/pov_projection.h"

namespace {

namespace pp = fb::pov_projection;

constexpr fb_param_desc kParams[] = {
    {"variant", FB_PARAM_INT, "1", "", nullptr, 1, 4,
     "POV-Ray's cylinder camera type: 1, 3 axis up; 2, 4 axis right; 3, 4 orthographic along it"},
    pp::kAngleParam,
    pp::kRightLengthParam,
    pp::kUpLengthParam,
};
constexpr auto kVariant = fb::param<int>(kParams, "variant");
constexpr auto kAngle = fb::param<double>(kParams, "angle_deg");
constexpr auto kRightLength = fb::param<double>(kParams, "right_length_m");
constexpr auto kUpLength = fb::param<double>(kParams, "up_length_m");

class PovCylinder {
 public:
  PovCylinder(const fb_value* values, const fb_camera_setup& setup)
      : image_(setup),
        variant_(kVariant(values)),
        angle_rad_(kAngle(values) * pp::kRadiansPerDegree),
        right_(kRightLength(values)),
        up_(kUpLength(values)) {}

  uint32_t needs() const { return 0; }

  std::string describe() const {
    const double angle_deg = angle_rad_ / pp::kRadiansPerDegree;
    const bool up_axis = variant_ == 1 || variant_ == 3;
    const double length_m = up_axis ? up_ : right_;
    return pp::text_of("field of view: %.6g deg around the %s axis; %.6g m along it %s\n",
                       angle_deg, up_axis ? "up" : "right", length_m,
                       variant_ <= 2 ? "at distance 1 (rays from the camera)"
                                     : "(rays from a line: orthographic)");
  }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    const pp::ImagePoint p = image_.point(s);
    const double a = p.x0 * angle_rad_, b = p.y0 * angle_rad_;
    switch (variant_) {
      case 1:
        return image_.set_ray(std::sin(a), p.y0 * up_, std::cos(a), ray);
      case 2:
        return image_.set_ray(p.x0 * right_, std::sin(b), std::cos(b), ray);
      case 3:
        return image_.set_ray(std::sin(a), 0, std::cos(a), ray, 0, p.y0 * up_);
      default:
        return image_.set_ray(0, std::sin(b), std::cos(b), ray, p.x0 * right_, 0);
    }
  }

 private:
  pp::PovImage image_;
  int variant_;
  double angle_rad_, right_, up_;
};

constexpr fb_camera_api kApi = fb::camera_api<PovCylinder>();
constexpr fb_plugin kPlugin = fb::describe(
    "pov_cylinder", "1.0.0",
    "POV-Ray's cylinder cameras 1-4: angle around an up or right axis, length along it", kParams,
    kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
