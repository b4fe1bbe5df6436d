// Camera `central_cylindrical`: Blender 4.0's central cylindrical panorama. Longitude is linear in
// u, and height on a cylinder of the given radius around the vertical axis linear in v; rays
// leave the axis through the cylinder (Cycles 4.x central_cylindrical_to_direction).
// filmback/panorama.h has the mapping.
#include <filmback/panorama.h>
#include <filmback/plugin_sdk.h>

namespace {

namespace pano = fb::panorama;

// Blender 4.x's central_cylindrical_range_u_min/max (longitude), _v_min/max (height) and
// central_cylindrical_radius, the last three lengths.
constexpr fb_param_desc kOwnParams[] = {
    {"central_cylindrical_range_u_min_rad", FB_PARAM_FLOAT, "-3.141592653589793", "rad", nullptr,
     -1e3, 1e3, "longitude of the image's left edge, positive rightwards"},
    {"central_cylindrical_range_u_max_rad", FB_PARAM_FLOAT, "3.141592653589793", "rad", nullptr,
     -1e3, 1e3, "longitude of the image's right edge"},
    {"central_cylindrical_range_v_min_m", FB_PARAM_FLOAT, "-1", "m", nullptr, -1e6, 1e6,
     "height on the cylinder of the image's bottom edge"},
    {"central_cylindrical_range_v_max_m", FB_PARAM_FLOAT, "1", "m", nullptr, -1e6, 1e6,
     "height on the cylinder of the image's top edge"},
    {"central_cylindrical_radius_m", FB_PARAM_FLOAT, "1", "m", nullptr, 1e-5, 1e6,
     "the cylinder's radius"},
};
constexpr auto kSchema = pano::with_lens(kOwnParams);
constexpr auto kUMin = fb::param<double>(kSchema.params, "central_cylindrical_range_u_min_rad");
constexpr auto kUMax = fb::param<double>(kSchema.params, "central_cylindrical_range_u_max_rad");
constexpr auto kVMin = fb::param<double>(kSchema.params, "central_cylindrical_range_v_min_m");
constexpr auto kVMax = fb::param<double>(kSchema.params, "central_cylindrical_range_v_max_m");
constexpr auto kRadius = fb::param<double>(kSchema.params, "central_cylindrical_radius_m");

struct CentralCylindrical {
  pano::AngleRange longitude, height;  // height per unit radius
  CentralCylindrical(const fb_value* values, const fb_camera_setup&)
      : longitude{kUMin(values), kUMax(values)},
        height{kVMin(values) / kRadius(values), kVMax(values) / kRadius(values)} {}
  fb::Vec3d direction(pano::Film f) const {
    return pano::central_cylindrical_direction(f, longitude, height);
  }
  std::string describe() const {
    return pano::text("field of view: %.6g deg horizontal x %.6g deg vertical\n",
                      pano::degrees(std::abs(longitude.max - longitude.min)),
                      pano::degrees(std::abs(std::atan(height.max) - std::atan(height.min))));
  }
};

constexpr fb_camera_api kApi = fb::camera_api<pano::Camera<CentralCylindrical>>();
constexpr fb_plugin kPlugin =
    fb::describe("central_cylindrical", "1.1.0",
                 "Blender 4's central cylindrical panorama over its longitude and height ranges",
                 kSchema.params, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
