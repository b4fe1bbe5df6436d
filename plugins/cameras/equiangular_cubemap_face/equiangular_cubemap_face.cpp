// Camera `equiangular_cubemap_face`: Blender 4.0's equiangular cubemap face, one 90 degree face of
// Google's equi-angular cubemap, the angle (not its tangent) linear across the image on each axis.
// filmback/panorama.h has the mapping.
#include <filmback/panorama.h>
#include <filmback/plugin_sdk.h>

namespace {

namespace pano = fb::panorama;

struct CubemapFace {
  CubemapFace(const fb_value*, const fb_camera_setup&) {}
  fb::Vec3d direction(pano::Film f) const { return pano::cubemap_face_direction(f); }
  std::string describe() const { return "field of view: 90 deg horizontal x 90 deg vertical\n"; }
};

constexpr auto kSchema = pano::with_lens();
constexpr fb_camera_api kApi = fb::camera_api<pano::Camera<CubemapFace>>();
constexpr fb_plugin kPlugin = fb::describe(
    "equiangular_cubemap_face", "1.1.0",
    "Blender 4's equiangular cubemap face: 90 degrees with the angle linear across the image",
    kSchema.params, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
