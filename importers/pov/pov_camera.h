// POV-Ray 3.7's camera statement as filmback's physical camera (docs/pov.md "Camera"): the fixed
// evaluation order of Parse_Camera (right, direction, angle, up, sky, location, look_at,
// orthographic re-size, focal_point, transforms), then the resulting direction/right/up vectors,
// which span exactly |right| x |up| at distance |direction| whatever the image size, become a
// pinhole, thin-lens or orthographic camera in the right-handed world of pov_space.h, or one of
// POV-Ray's other projections (docs/camera-model.md "POV-Ray's projections").
#pragma once

#include <cstdint>
#include <optional>

#include <filmback/vec.h>

#include "core/scene/camera.h"
#include "core/util/diagnostics.h"
#include "importers/pov/pov_scene.h"

namespace fb::pov {

// The camera as POV-Ray renders it (camera.h's Camera after Parse_Camera), in POV-Ray's space.
// A perspective ray through the image point (x0, y0) in (-1/2, 1/2)^2, x0 right and y0 up, is
// location + t (direction + x0 right + y0 up); an orthographic one starts at
// location + x0 right + y0 up and runs along direction.
struct PovCameraVectors {
  CameraType type = CameraType::kPerspective;
  Vec3d location{0, 0, 0}, direction{0, 0, 1}, right{1.33, 0, 0}, up{0, 1, 0};
  double focal_distance = 1;  // of the focal plane, along direction (Euclidean to focal_point)
  bool focal_blur = false;    // aperture != 0 and blur_samples > 0
  double aperture = 0;
  // The other types' angles (Camera::Init's defaults), in degrees: `angle` of fisheye,
  // ultra_wide_angle and cylinder; spherical's `angle H, V` (V = H / 2 when not given).
  int cylinder_type = 0;  // 1 to 4 for CameraType::kCylinder
  double angle_deg = 90, angle_h_deg = 360, angle_v_deg = 180;
};

// The camera type's keyword as a scene writes it: "perspective", "fisheye", "cylinder", ...
const char* keyword_of(CameraType type);

// Applies POV-Ray's order and defaults. Throws InputError where POV-Ray stops with an error
// (a negative angle, angle >= 180 for perspective and orthographic, a cylinder type other than 1
// to 4, look_at at the location); warns where POV-Ray warns about a camera looking
// along sky.
PovCameraVectors evaluate_camera(const CameraStatement& statement, Diagnostics& diagnostics);

struct PovCamera {
  SceneCamera camera;
  // Pixel width / height: |right| / |up| need not be W / H. The render reads it from
  // Scene::settings.pixel_aspect, where the importer puts it.
  double pixel_aspect = 1;
};

// No statement: POV-Ray's default camera. The other camera types (fisheye, ultra_wide_angle,
// omnimax, panoramic, cylinder 1-4, spherical) become a panoramic projection, rendered by the
// camera plugin pov_<type> with the values of SceneCamera::model, each with its place in the
// .pov. Features the camera model cannot render exactly (a camera normal, focal blur beyond the
// perspective camera, right not perpendicular to up) are warned about, with the error they leave,
// in `diagnostics`.
PovCamera convert_camera(const std::optional<CameraStatement>& statement, uint32_t width_px,
                         uint32_t height_px, Diagnostics& diagnostics);

}  // namespace fb::pov
