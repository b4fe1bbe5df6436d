// Camera `pov_omnimax`: POV-Ray 3.7's `omnimax` camera (tracepixel.cpp CreateCameraRay,
// OMNIMAX_CAMERA; docs/camera-model.md "POV-Ray's projections"), a dome projection with its own
// fixed lens: no angle.
//
// The image point becomes (x, y) = (2 x0, 2 y0) in [-1, 1] (pov_projection.h), fitted to the
// aspect k = |right| / |up|: for k > 1 the circle is anchored at the top of the image,
// y = (y - 1) / min(k, 1.283458) + 1, and for k > 1.283458 also widened, x *= k / 1.283458; for
// k <= 1, y /= k. Beyond the unit circle, no ray. The radius r gives the angle from the view axis
// theta = 1.411269 r - 0.09439 r^3 + 0.25674 r^5 (1.574 rad, 90.2 degrees, at r = 1), the image
// angle phi as the fisheye's, and rays more than 45 degrees below the plane of right and direction
// (sin(phi) sin(theta) < tan(135 degrees) cos(theta)) are not traced either.
#include <filmback/plugin_sdk.h>

#include "plugins/cameras/pov_projection/pov_projection.h"

namespace {

namespace pp = fb::pov_projection;

constexpr fb_param_desc kParams[] = {pp::kRightLengthParam, pp::kUpLengthParam};
constexpr auto kRightLength = fb::param<double>(kParams, "right_length_m");
constexpr auto kUpLength = fb::param<double>(kParams, "up_length_m");

// POV-Ray's constants, as it writes them.
constexpr double kWideAspect = 1.283458;
constexpr double kTheta1 = 1.411269, kTheta3 = -0.09439, kTheta5 = 0.25674;

class PovOmnimax {
 public:
  PovOmnimax(const fb_value* values, const fb_camera_setup& setup)
      : image_(setup),
        aspect_(kRightLength(values) / kUpLength(values)),
        floor_slope_(std::tan(135 * pp::kRadiansPerDegree)) {}

  uint32_t needs() const { return 0; }

  std::string describe() const {
    const double edge_rad = kTheta1 + kTheta3 + kTheta5;
    return pp::text_of(
        "field of view: %.6g deg across the dome's circle (%.6g deg from the axis at its edge); "
        "no rays more than 45 deg below the axis\n",
        2 * edge_rad / pp::kRadiansPerDegree, edge_rad / pp::kRadiansPerDegree);
  }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    const pp::ImagePoint p = image_.point(s);
    double x = 2 * p.x0, y = 2 * p.y0;
    if (aspect_ > 1) {
      if (aspect_ > kWideAspect) x *= aspect_ / kWideAspect;
      y = (y - 1) / std::min(aspect_, kWideAspect) + 1;
    } else {
      y /= aspect_;
    }
    const double r = std::sqrt(x * x + y * y);
    if (r > 1) return pp::PovImage::set_no_ray(ray);
    const double r2 = r * r;
    const double theta = r * (kTheta1 + r2 * (kTheta3 + r2 * kTheta5));
    const double sin_phi = r > 0 ? y / r : 0;
    if (sin_phi * std::sin(theta) < floor_slope_ * std::cos(theta))
      return pp::PovImage::set_no_ray(ray);
    pp::set_polar_ray(image_, x, y, r, theta, ray);
  }

 private:
  pp::PovImage image_;
  double aspect_, floor_slope_;
};

constexpr fb_camera_api kApi = fb::camera_api<PovOmnimax>();
constexpr fb_plugin kPlugin =
    fb::describe("pov_omnimax", "1.0.0",
                 "POV-Ray's omnimax camera: a fixed dome lens of about 180 degrees", kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
