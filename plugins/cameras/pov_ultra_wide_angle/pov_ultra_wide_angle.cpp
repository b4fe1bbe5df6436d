// Camera `pov_ultra_wide_angle`: POV-Ray 3.7's `ultra_wide_angle` camera (tracepixel.cpp
// CreateCameraRay, ULTRA_WIDE_ANGLE_CAMERA; docs/camera-model.md "POV-Ray's projections").
//
// The image point (x0, y0) (pov_projection.h) becomes the angles a = x0 angle across and
// b = y0 angle |up| / |right| up (square pixels when |right| / |up| is the image's aspect), and
// the ray sin(a) right + sin(b) up + cos(a) cos(b) direction, normalised. Every point has a
// ray: with angle above 180 the edges look backwards.
#include <filmback/plugin_sdk.h>

#include "plugins/cameras/pov_projection/pov_projection.h"

namespace {

namespace pp = fb::pov_projection;

class PovUltraWideAngle {
 public:
  PovUltraWideAngle(const fb_value* values, const fb_camera_setup& setup)
      : PovUltraWideAngle(pp::angle_and_lengths(values), setup) {}
  PovUltraWideAngle(const pp::AngleAndLengths& v, const fb_camera_setup& setup)
      : image_(setup), across_rad_(v.angle_rad), up_rad_(v.angle_rad * v.up_m / v.right_m) {}

  uint32_t needs() const { return 0; }

  std::string describe() const {
    return pp::text_of("field of view: %.6g deg across, %.6g deg up\n",
                       across_rad_ / pp::kRadiansPerDegree, up_rad_ / pp::kRadiansPerDegree);
  }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    const pp::ImagePoint p = image_.point(s);
    const double a = p.x0 * across_rad_, b = p.y0 * up_rad_;
    // Never all zero: sin(a) = sin(b) = 0 leaves cos(a) cos(b) = +-1.
    image_.set_ray(std::sin(a), std::sin(b), std::cos(a) * std::cos(b), ray);
  }

 private:
  pp::PovImage image_;
  double across_rad_, up_rad_;
};

constexpr fb_camera_api kApi = fb::camera_api<PovUltraWideAngle>();
constexpr fb_plugin kPlugin = fb::describe(
    "pov_ultra_wide_angle", "1.0.0",
    "POV-Ray's ultra_wide_angle camera: angle across the image, sines of the two angles",
    pp::kAngleAndLengthsParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
