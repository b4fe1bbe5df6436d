// Camera `fisheye_equisolid`: Cycles' equisolid-angle fisheye, r = 2 f sin(theta / 2) in mm on the
// imaged sensor (the shot's sensor size and fit), cut at theta = fov / 2; outside, weight 0.
// filmback/panorama.h has the mapping.
#include <filmback/panorama.h>
#include <filmback/plugin_sdk.h>

namespace {

namespace pano = fb::panorama;

// Blender's fisheye_lens and fisheye_fov (Camera > Panoramic > Fisheye Equisolid).
constexpr fb_param_desc kOwnParams[] = {
    {"fisheye_lens_mm", FB_PARAM_FLOAT, "10.5", "mm", nullptr, 1e-3, 1e4,
     "the fisheye's focal length f in r = 2 f sin(theta / 2)"},
    {"fisheye_fov_rad", FB_PARAM_FLOAT, "3.141592653589793", "rad", nullptr, 1e-3,
     2 * pano::kPi + 1e-6, "full angle imaged, at most 2 pi; beyond it, black"},
};
constexpr auto kSchema = pano::with_lens(kOwnParams);
constexpr auto kLens = fb::param<double>(kSchema.params, "fisheye_lens_mm");
constexpr auto kFov = fb::param<double>(kSchema.params, "fisheye_fov_rad");

struct Equisolid {
  double lens_mm, fov_rad;
  fb::Vec2d sensor_mm;
  Equisolid(const fb_value* values, const fb_camera_setup& s)
      : lens_mm(kLens(values)), fov_rad(kFov(values)), sensor_mm(pano::imaged_sensor_mm(s)) {
    if (const char* problem = pano::imaged_sensor_problem(s)) throw std::invalid_argument(problem);
  }
  fb::Vec3d direction(pano::Film f) const {
    return pano::equisolid_direction(f, lens_mm, fov_rad, sensor_mm);
  }
};

constexpr fb_camera_api kApi = fb::camera_api<pano::Camera<Equisolid>>();
constexpr fb_plugin kPlugin = fb::describe(
    "fisheye_equisolid", "1.0.0",
    "Cycles' equisolid fisheye from Blender's fisheye lens, field of view and the shot's sensor",
    kSchema.params, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
