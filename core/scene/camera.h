// A scene camera as a physical parameter set (Blender's), plus its placement. Every importer
// converts into this; the render turns it into an fb_camera_setup for the camera plugin.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <filmback/plugin_abi.h>

#include "core/math/transform.h"
#include "core/scene/animation.h"
#include "core/scene/sensor_fit.h"
#include "core/scene/value_origin.h"

namespace fb {

struct PhysicalCamera {
  uint32_t projection = FB_PROJECTION_PERSPECTIVE;
  double focal_length_mm = 50.0;
  double sensor_width_mm = 36.0;
  double sensor_height_mm = 24.0;
  uint32_t sensor_fit = FB_SENSOR_FIT_AUTO;
  double shift_x = 0.0, shift_y = 0.0;  // fractions of the fitted side
  double ortho_scale_m = 1.0;
  double clip_near_m = 0.1;
  double clip_far_m = HUGE_VAL;
  double fstop = HUGE_VAL;             // a pinhole unless the shot says otherwise
  double focus_distance_m = HUGE_VAL;  // along the view axis
  uint32_t aperture_blades = 0;        // 0: round
  double aperture_rotation_rad = 0.0;
  double aperture_ratio = 1.0;  // anamorphic bokeh, as Cycles

  bool has_aperture() const { return std::isfinite(fstop); }
};

// Blender's F-Stop as a scene or --fstop gives it, the one place that reads it: 0 (Blender's depth
// of field off) and infinity mean a pinhole, HUGE_VAL; otherwise an f-number in (0, kMaxFstop].
// Nothing otherwise: the caller reports kFstopExpected, naming where the number came from.
constexpr double kMaxFstop = 1e6;
constexpr const char* kFstopExpected = "expected 0 (a pinhole) or an f-number in (0, 1e6]";
std::optional<double> fstop_from(double n);

// The values of a PhysicalCamera one by one, under the names of the FILMBACK_blender extension
// (docs/blender.md, "What is carried"), so that each can say where it came from.
enum class CameraValue : uint8_t {
  kFocalLength,
  kSensorWidth,
  kSensorHeight,
  kSensorFit,
  kShiftX,
  kShiftY,
  kOrthoScale,
  kClipNear,
  kClipFar,
  kFstop,
  kFocusDistance,
  kApertureBlades,
  kApertureRotation,
  kApertureRatio,
  kCount
};
constexpr size_t kCameraValueCount = size_t(CameraValue::kCount);
const char* camera_value_name(CameraValue v);  // "focal_length_mm"
// The value as a number (the sensor fit and blade count as their numbers).
double camera_value(const PhysicalCamera& camera, CameraValue v);
void set_camera_value(PhysicalCamera& camera, CameraValue v, double x);

// Where each value of a scene camera came from, indexed by CameraValue.
using CameraOrigins = std::array<ValueOrigin, kCameraValueCount>;

// How the sensor turns light into pixel values (docs/camera-model.md, "Exposure").
struct SensorResponse {
  uint32_t model = FB_SENSOR_SIMPLE;
  double exposure_time_s = 1.0;  // PHYSICAL only
  double iso = 100.0;            // PHYSICAL only
};

// Lens values that vary from frame to frame: Blender's animated focal length, focus distance (or
// focus object), f-stop and shift, one value per frame from first_frame on, linear in between and
// held beyond the ends (docs/camera-model.md, "Animated lenses"). Each value has its own list;
// an empty one is not tracked.
struct LensTrack {
  static constexpr CameraValue kTracked[] = {CameraValue::kFocalLength, CameraValue::kFocusDistance,
                                             CameraValue::kFstop, CameraValue::kShiftX,
                                             CameraValue::kShiftY};
  double first_frame = 0;
  std::array<std::vector<double>, kCameraValueCount> values;

  bool tracks(CameraValue v) const { return !values[size_t(v)].empty(); }
  double at(CameraValue v, double frame) const;  // tracks(v)
  // Every tracked value of `camera` set to the track's at `frame`.
  void apply(double frame, PhysicalCamera& camera) const;
};

// A projection beyond Blender's perspective and orthographic ones (docs/camera-model.md): the
// scene's name for it ("equirectangular", "fisheye_equisolid", a POV-Ray camera type) and its
// values under the names of the camera plugin's parameters. The shot plan maps the name to a
// plugin (core/render/shot_plan.cpp, the one table of plugin names) and hands it the numbers.
struct CameraModel {
  std::string kind;
  std::vector<NamedNumber> numbers;
  ValueOrigin origin;  // where the scene names the kind
};

struct SceneCamera {
  std::string name;    // the glTF camera's name, else its node's name
  std::string source;  // where it came from: "nodes[3] (cameras[0])"
  PhysicalCamera physical;
  Transform world_from_camera;            // rest pose, scale removed: looks down -Z, +Y up
  uint32_t node_index = kNoNode;          // in Scene::hierarchy, whose animation may move it
  std::optional<double> intended_aspect;  // width / height the shot was made for
  std::optional<LensTrack> lens_track;    // replaces the values it tracks at the shot's frame
  std::optional<CameraModel> model;       // when physical.projection is FB_PROJECTION_PANORAMIC
  // A tracked clip's lens distortion as the projective cameras' parameters (each required;
  // filmback/lens_distortion.h); empty: none.
  std::vector<NamedNumber> lens_distortion;
  CameraOrigins origins;  // where each value of `physical` came from
  const ValueOrigin& origin(CameraValue v) const { return origins[size_t(v)]; }
};

// The quantities `filmback info` reports, for a given image size.
struct CameraQuantities {
  double horizontal_fov_deg, vertical_fov_deg;  // full angles of the view plane extents
  double imaged_sensor_width_mm, imaged_sensor_height_mm;
  double equivalent_35mm_width_mm;     // f * 36 / imaged width
  double equivalent_35mm_diagonal_mm;  // f * 43.27 / imaged diagonal
  bool horizontal_fit;
};

fb_camera_setup make_camera_setup(const PhysicalCamera& camera, uint32_t width_px,
                                  uint32_t height_px, double pixel_aspect = 1.0,
                                  const SensorResponse& sensor = {});
CameraQuantities describe_camera(const PhysicalCamera& camera, uint32_t width_px,
                                 uint32_t height_px);

}  // namespace fb
