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
  // The image circle (radius 2 f sin(fov / 4)), the angles it spans across the frame, and the
  // fisheye of the same diagonal angle on 35 mm film.
  std::string describe() const {
    const double circle_mm = 2 * lens_mm * std::sin(fov_rad / 4);
    const auto theta_deg = [&](double r_mm) {
      return pano::degrees(2 * std::asin(std::min(r_mm, circle_mm) / (2 * lens_mm)));
    };
    return pano::fisheye_fov_text({sensor_mm.x / 2, sensor_mm.y / 2}, theta_deg) +
           pano::text(
               "image circle: %.6g mm across (%.6g deg) on the imaged %.6g x %.6g mm sensor\n"
               "35 mm equivalent fisheye lens: %.6g mm (diagonal-based, 43.27 mm)\n",
               2 * circle_mm, pano::degrees(fov_rad), sensor_mm.x, sensor_mm.y,
               pano::equivalent_35mm_mm(lens_mm, sensor_mm));
  }
};

constexpr fb_camera_api kApi = fb::camera_api<pano::Camera<Equisolid>>();
constexpr fb_plugin kPlugin = fb::describe(
    "fisheye_equisolid", "1.1.0",
    "Cycles' equisolid fisheye from Blender's fisheye lens, field of view and the shot's sensor",
    kSchema.params, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
