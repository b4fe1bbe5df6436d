// Camera `pov_spherical`: POV-Ray 3.7's `spherical` camera (tracepixel.cpp CreateCameraRay,
// SPHERICAL_CAMERA; docs/camera-model.md "POV-Ray's projections"), an equirectangular panorama of
// `angle H, V` degrees (360 x 180 by default; V defaults to H / 2 in the scene).
//
// With (x0, y0) the image point (pov_projection.h), the longitude h = x0 H and latitude
// v = y0 V: POV-Ray turns direction about right by -v, then about up by h (right-hand rule in its
// space), which for a frame whose (up x direction) . right is positive is
// cos(v) sin(h) right + sin(v) up + cos(v) cos(h) direction. A frame of the other handedness turns
// the other way about both axes: the importer gives this plugin right and up negated then
// (importers/pov/pov_camera.cpp), so this one formula serves both. Angles beyond 360 x 180 wrap:
// the image repeats.
#include <filmback/plugin_sdk.h>

#include "plugins/cameras/pov_projection/pov_projection.h"

namespace {

namespace pp = fb::pov_projection;

constexpr fb_param_desc kParams[] = {
    {"angle_h_deg", FB_PARAM_FLOAT, "360", "deg", nullptr, 0, pp::kMaxAngleDeg,
     "horizontal field of view: longitudes across the image"},
    {"angle_v_deg", FB_PARAM_FLOAT, "180", "deg", nullptr, 0, pp::kMaxAngleDeg,
     "vertical field of view: latitudes up the image"},
};
constexpr auto kAngleH = fb::param<double>(kParams, "angle_h_deg");
constexpr auto kAngleV = fb::param<double>(kParams, "angle_v_deg");

class PovSpherical {
 public:
  PovSpherical(const fb_value* values, const fb_camera_setup& setup)
      : image_(setup),
        h_rad_(kAngleH(values) * pp::kRadiansPerDegree),
        v_rad_(kAngleV(values) * pp::kRadiansPerDegree) {}

  uint32_t needs() const { return 0; }

  std::string describe() const {
    const double h_deg = h_rad_ / pp::kRadiansPerDegree, v_deg = v_rad_ / pp::kRadiansPerDegree;
    return pp::text_of("field of view: %.6g deg across, %.6g deg up; %.6g x %.6g deg a pixel\n",
                       h_deg, v_deg, h_deg / image_.width_px(), v_deg / image_.height_px());
  }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    const pp::ImagePoint p = image_.point(s);
    const double h = p.x0 * h_rad_, v = p.y0 * v_rad_;
    image_.set_ray(std::cos(v) * std::sin(h), std::sin(v), std::cos(v) * std::cos(h), ray);
  }

 private:
  pp::PovImage image_;
  double h_rad_, v_rad_;
};

constexpr fb_camera_api kApi = fb::camera_api<PovSpherical>();
constexpr fb_plugin kPlugin = fb::describe(
    "pov_spherical", "1.0.0",
    "POV-Ray's spherical camera: longitude and latitude linear across the image", kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
