// Camera `fisheye_equidistant`: Cycles' equidistant fisheye, theta = r fov / 2 with r = 1 on the
// circle inscribed in the image (an ellipse on a non-square image, as Cycles renders it); outside
// it, weight 0. filmback/panorama.h has the mapping.
#include <filmback/panorama.h>
#include <filmback/plugin_sdk.h>

namespace {

namespace pano = fb::panorama;

// Blender's Field of View (fisheye_fov), 10 to 360 degrees; the upper bound admits 2 pi rounded
// to float, as Blender stores it.
constexpr fb_param_desc kOwnParams[] = {
    {"fisheye_fov_rad", FB_PARAM_FLOAT, "3.141592653589793", "rad", nullptr, 1e-3,
     2 * pano::kPi + 1e-6, "full angle the inscribed circle spans, at most 2 pi"},
};
constexpr auto kSchema = pano::with_lens(kOwnParams);
constexpr auto kFov = fb::param<double>(kSchema.params, "fisheye_fov_rad");

struct Equidistant {
  double fov_rad;
  Equidistant(const fb_value* values, const fb_camera_setup&) : fov_rad(kFov(values)) {}
  fb::Vec3d direction(pano::Film f) const { return pano::equidistant_direction(f, fov_rad); }
  std::string describe() const {
    return pano::text(
        "field of view: %.6g deg across the circle inscribed in the frame (an ellipse on a "
        "non-square frame): %.6g deg horizontal x %.6g deg vertical\n",
        pano::degrees(fov_rad), pano::degrees(fov_rad), pano::degrees(fov_rad));
  }
};

constexpr fb_camera_api kApi = fb::camera_api<pano::Camera<Equidistant>>();
constexpr fb_plugin kPlugin =
    fb::describe("fisheye_equidistant", "1.1.0",
                 "Cycles' equidistant fisheye: the angle from the axis grows linearly with the "
                 "radius, over Blender's field of view",
                 kSchema.params, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
