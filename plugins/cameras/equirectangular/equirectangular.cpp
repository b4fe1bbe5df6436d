// Camera `equirectangular`: Cycles' equirectangular panorama. Longitude (rightwards from the view
// axis) and latitude (upwards) are linear across the image over Blender's ranges (Camera >
// Panoramic > Latitude/Longitude Min/Max); filmback/panorama.h has the mapping.
#include <filmback/panorama.h>
#include <filmback/plugin_sdk.h>

namespace {

namespace pano = fb::panorama;

constexpr double kHalfPi = pano::kPi / 2, kTwoPi = 2 * pano::kPi;

// Blender's RNA names, in radians, with its bounds.
constexpr fb_param_desc kOwnParams[] = {
    {"latitude_min_rad", FB_PARAM_FLOAT, "-1.5707963267948966", "rad", nullptr, -kHalfPi - 1e-6,
     kHalfPi + 1e-6, "latitude of the image's bottom edge"},
    {"latitude_max_rad", FB_PARAM_FLOAT, "1.5707963267948966", "rad", nullptr, -kHalfPi - 1e-6,
     kHalfPi + 1e-6, "latitude of the image's top edge"},
    {"longitude_min_rad", FB_PARAM_FLOAT, "-3.141592653589793", "rad", nullptr, -kTwoPi - 1e-6,
     kTwoPi + 1e-6, "longitude of the image's left edge, positive rightwards"},
    {"longitude_max_rad", FB_PARAM_FLOAT, "3.141592653589793", "rad", nullptr, -kTwoPi - 1e-6,
     kTwoPi + 1e-6, "longitude of the image's right edge"},
};
constexpr auto kSchema = pano::with_lens(kOwnParams);
constexpr auto kLatitudeMin = fb::param<double>(kSchema.params, "latitude_min_rad");
constexpr auto kLatitudeMax = fb::param<double>(kSchema.params, "latitude_max_rad");
constexpr auto kLongitudeMin = fb::param<double>(kSchema.params, "longitude_min_rad");
constexpr auto kLongitudeMax = fb::param<double>(kSchema.params, "longitude_max_rad");

struct Equirectangular {
  pano::AngleRange longitude, latitude;
  Equirectangular(const fb_value* values, const fb_camera_setup&)
      : longitude{kLongitudeMin(values), kLongitudeMax(values)},
        latitude{kLatitudeMin(values), kLatitudeMax(values)} {}
  fb::Vec3d direction(pano::Film f) const {
    return pano::equirectangular_direction(f, longitude, latitude);
  }
  std::string describe() const {
    using pano::degrees;
    return pano::text(
        "field of view: %.6g deg horizontal (longitude %.6g to %.6g deg) x %.6g deg vertical "
        "(latitude %.6g to %.6g deg)\n",
        degrees(std::abs(longitude.max - longitude.min)), degrees(longitude.min),
        degrees(longitude.max), degrees(std::abs(latitude.max - latitude.min)),
        degrees(latitude.min), degrees(latitude.max));
  }
};

constexpr fb_camera_api kApi = fb::camera_api<pano::Camera<Equirectangular>>();
constexpr fb_plugin kPlugin =
    fb::describe("equirectangular", "1.1.0",
                 "Cycles' equirectangular panorama over Blender's latitude and longitude ranges",
                 kSchema.params, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
