// Camera `pov_panoramic`: POV-Ray 3.7's `panoramic` camera (tracepixel.cpp CreateCameraRay,
// PANORAMIC_CAMERA, "from Graphic Gems III"; docs/camera-model.md "POV-Ray's projections"), a
// cylindrical panorama 180 degrees wide. No angle.
//
// Across, the longitude l = pi (1/2 - x0) from right (left edge: -right; right edge: +right);
// up, the latitude m = pi y0 as a height tan(m) on the cylinder. POV-Ray combines its right, up
// and direction vectors as they are, not normalised: the ray is
// cos(l) right + tan(m) up + sin(l) direction, so their lengths are parameters. At the top and
// bottom edges (|m| within 1e-10 of pi/2) POV-Ray puts +-2e10 for tan(m): straight up or down.
#include <filmback/plugin_sdk.h>

#include "plugins/cameras/pov_projection/pov_projection.h"

namespace {

namespace pp = fb::pov_projection;

constexpr fb_param_desc kParams[] = {
    pp::kRightLengthParam,
    pp::kUpLengthParam,
    {"direction_length_m", FB_PARAM_FLOAT, "1", "m", nullptr, 1e-12, 1e12,
     "length of POV-Ray's direction vector"},
};
constexpr auto kRightLength = fb::param<double>(kParams, "right_length_m");
constexpr auto kUpLength = fb::param<double>(kParams, "up_length_m");
constexpr auto kDirectionLength = fb::param<double>(kParams, "direction_length_m");

// POV-Ray's EPSILON and BOUND_HUGE (frame.h).
constexpr double kPovEpsilon = 1e-10, kPovBoundHuge = 2e10;

class PovPanoramic {
 public:
  PovPanoramic(const fb_value* values, const fb_camera_setup& setup)
      : image_(setup),
        right_(kRightLength(values)),
        up_(kUpLength(values)),
        direction_(kDirectionLength(values)) {}

  uint32_t needs() const { return 0; }

  std::string describe() const {
    return pp::text_of(
        "field of view: 180 deg across (longitude), latitudes up to +-90 deg as heights tan(m) on "
        "a cylinder; right : up : direction = %.6g : %.6g : %.6g\n",
        right_, up_, direction_);
  }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    constexpr double kPi = std::numbers::pi;
    const pp::ImagePoint p = image_.point(s);
    const double longitude = kPi * (0.5 - p.x0), latitude = kPi * p.y0;
    const double height = std::abs(kPi / 2 - std::abs(latitude)) < kPovEpsilon
                              ? std::copysign(kPovBoundHuge, latitude)
                              : std::tan(latitude);
    image_.set_ray(std::cos(longitude) * right_, height * up_, std::sin(longitude) * direction_,
                   ray);
  }

 private:
  pp::PovImage image_;
  double right_, up_, direction_;
};

constexpr fb_camera_api kApi = fb::camera_api<PovPanoramic>();
constexpr fb_plugin kPlugin = fb::describe(
    "pov_panoramic", "1.0.0",
    "POV-Ray's panoramic camera: 180 degrees across, heights tan(latitude) on a cylinder", kParams,
    kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
