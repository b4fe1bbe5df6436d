// Camera `pov_fisheye`: POV-Ray 3.7's `fisheye` camera (tracepixel.cpp CreateCameraRay,
// FISHEYE_CAMERA; docs/camera-model.md "POV-Ray's projections").
//
// The image point (x0, y0) (pov_projection.h) becomes u = 2 x0 |right|, v = 2 y0 |up|: the circle
// u^2 + v^2 <= 1 is the fisheye's image (|right| = 1.33, |up| = 1 on a 4:3 image: a circle of
// the image's height), and beyond it POV-Ray traces no ray. The radius r = sqrt(u^2 + v^2) is the
// angle from the view axis in units of half the field of view, an equidistant fisheye:
// theta = r angle / 2, so the circle's edge sees angle / 2 off the axis (angle 360: straight back).
#include <filmback/plugin_sdk.h>

#include "plugins/cameras/pov_projection/pov_projection.h"

namespace {

namespace pp = fb::pov_projection;

class PovFisheye {
 public:
  PovFisheye(const fb_value* values, const fb_camera_setup& setup)
      : image_(setup), values_(pp::angle_and_lengths(values)) {}

  uint32_t needs() const { return 0; }

  // The circle u^2 + v^2 = 1 in pixels: u = 1 at x0 = 1 / (2 |right|).
  std::string describe() const {
    return pp::text_of(
        "field of view: %.6g deg across the image circle (%.6g deg from the axis at its edge)\n"
        "image circle: %.6g px wide, %.6g px high, centred; no rays outside it\n",
        values_.angle_rad / pp::kRadiansPerDegree, values_.angle_rad / pp::kRadiansPerDegree / 2,
        image_.width_px() / values_.right_m, image_.height_px() / values_.up_m);
  }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    const pp::ImagePoint p = image_.point(s);
    const double u = 2 * p.x0 * values_.right_m, v = 2 * p.y0 * values_.up_m;
    const double r = std::sqrt(u * u + v * v);
    if (r > 1) return pp::PovImage::set_no_ray(ray);
    pp::set_polar_ray(image_, u, v, r, r * values_.angle_rad / 2, ray);
  }

 private:
  pp::PovImage image_;
  pp::AngleAndLengths values_;
};

constexpr fb_camera_api kApi = fb::camera_api<PovFisheye>();
constexpr fb_plugin kPlugin =
    fb::describe("pov_fisheye", "1.0.0",
                 "POV-Ray's fisheye camera: equidistant, angle across the circle of |right| x |up|",
                 pp::kAngleAndLengthsParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
