// Camera `mirrorball`: Cycles' mirror ball, the image of a mirrored sphere seen from behind the
// camera (the view axis at the centre, straight behind on the rim); outside the inscribed circle,
// weight 0. filmback/panorama.h has the mapping.
#include <filmback/panorama.h>
#include <filmback/plugin_sdk.h>

namespace {

namespace pano = fb::panorama;

struct MirrorBall {
  static constexpr bool kMirrorBall = true;  // Cycles' aperture frame (panorama.h)
  MirrorBall(const fb_value*, const fb_camera_setup&) {}
  fb::Vec3d direction(pano::Film f) const { return pano::mirrorball_direction(f); }
  std::string describe() const {
    return "field of view: 360 deg, the whole sphere in the disc inscribed in the frame (straight "
           "back at its rim)\n";
  }
};

constexpr auto kSchema = pano::with_lens();
constexpr fb_camera_api kApi = fb::camera_api<pano::Camera<MirrorBall>>();
constexpr fb_plugin kPlugin = fb::describe(
    "mirrorball", "1.1.0", "Cycles' mirror ball panorama: the whole sphere", kSchema.params, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
