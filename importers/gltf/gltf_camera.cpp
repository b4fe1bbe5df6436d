#include "importers/gltf/gltf_camera.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/util/error.h"
#include "importers/gltf/gltf_json.h"
#include "importers/gltf/gltf_shot.h"

namespace fb::gltf {
namespace {

// Bounds on camera shapes, far beyond any real shot, so that no camera reaches the renderer with a
// view plane that float arithmetic cannot trace.
constexpr double kMinAspect = 1e-4;
constexpr double kMaxMagnification = 1e9;  // m

// Two descriptions of one shot agree when their vertical fields of view differ by at most this.
constexpr double kFovToleranceDeg = 0.01;

double vertical_fov_deg(const PhysicalCamera& camera, double aspect) {
  constexpr uint32_t kHeight = 100000;
  const auto width = uint32_t(std::max(1.0, std::round(aspect * kHeight)));
  return describe_camera(camera, width, kHeight).vertical_fov_deg;
}

// The core projection as Blender's physical set (docs/camera-model.md).
void read_core_projection(const tinygltf::Camera& g, const std::string& cpath,
                          const std::string& file, SceneCamera& camera) {
  PhysicalCamera& phys = camera.physical;
  if (g.type == "perspective") {
    const tinygltf::PerspectiveCamera& p = g.perspective;
    if (!(p.yfov > 0 && p.yfov < std::numbers::pi))
      throw_input(file, cpath + ".perspective.yfov",
                  number_text(p.yfov) + " is not a field of view (expected 0 < yfov < pi)");
    if (!(p.znear > 0))
      throw_input(file, cpath + ".perspective.znear", "expected a positive near clip distance");
    if (p.zfar != 0 && !(p.zfar > p.znear))
      throw_input(file, cpath + ".perspective.zfar", "expected zfar > znear");
    if (p.aspectRatio != 0 && !(p.aspectRatio >= kMinAspect && p.aspectRatio <= 1 / kMinAspect))
      throw_input(file, cpath + ".perspective.aspectRatio",
                  number_text(p.aspectRatio) + " is not an image shape (expected 1e-4 to 1e4)");
    // With an aspect ratio, a 36 mm sensor with AUTO fit, whose fitted side spans the larger
    // image side; without one, the vertical field of view is kept for any image shape.
    const double tan_half_y = std::tan(p.yfov / 2);
    phys.projection = FB_PROJECTION_PERSPECTIVE;
    if (p.aspectRatio > 0) {
      camera.intended_aspect = p.aspectRatio;
      const double tan_half_fitted = p.aspectRatio >= 1 ? tan_half_y * p.aspectRatio : tan_half_y;
      phys.focal_length_mm = phys.sensor_width_mm / (2 * tan_half_fitted);
    } else {
      phys.sensor_fit = FB_SENSOR_FIT_VERTICAL;
      phys.focal_length_mm = phys.sensor_height_mm / (2 * tan_half_y);
    }
    phys.clip_near_m = p.znear;
    phys.clip_far_m = p.zfar > 0 ? p.zfar : HUGE_VAL;  // absent zfar: infinite projection
  } else if (g.type == "orthographic") {
    const tinygltf::OrthographicCamera& o = g.orthographic;
    if (!(o.xmag > 0 && o.xmag <= kMaxMagnification && o.ymag > 0 && o.ymag <= kMaxMagnification &&
          o.xmag / o.ymag >= kMinAspect && o.xmag / o.ymag <= 1 / kMinAspect))
      throw_input(file, cpath + ".orthographic",
                  "expected xmag and ymag in (0, 1e9] m with a ratio from 1e-4 to 1e4");
    if (!(o.zfar > o.znear) || o.znear < 0)
      throw_input(file, cpath + ".orthographic", "expected 0 <= znear < zfar");
    phys.projection = FB_PROJECTION_ORTHOGRAPHIC;
    phys.ortho_scale_m = 2 * std::max(o.xmag, o.ymag);  // Blender: xmag = scale * w / max(w, h) / 2
    camera.intended_aspect = o.xmag / o.ymag;
    phys.clip_near_m = o.znear;
    phys.clip_far_m = o.zfar;
  } else {
    throw_input(file, cpath + ".type",
                "'" + g.type + "' is not a camera type (expected perspective or orthographic)");
  }
}

// EXT_camera_physical has no sensor fit: take the one under which its focal length and sensor
// give the file's yfov (AUTO, then horizontal, then vertical). False when none does.
bool fit_to_yfov(PhysicalCamera& phys, double yfov_deg, double aspect) {
  for (uint32_t fit : {FB_SENSOR_FIT_AUTO, FB_SENSOR_FIT_HORIZONTAL, FB_SENSOR_FIT_VERTICAL}) {
    phys.sensor_fit = fit;
    if (std::abs(vertical_fov_deg(phys, aspect) - yfov_deg) <= kFovToleranceDeg) return true;
  }
  return false;
}

const tinygltf::Value* extension(const tinygltf::Camera& g, const char* name) {
  const auto it = g.extensions.find(name);
  return it == g.extensions.end() ? nullptr : &it->second;
}

}  // namespace

SceneCamera read_camera(const tinygltf::Model& model, const tinygltf::Node& node,
                        const std::string& path, const Transform& world, uint32_t scene_node,
                        const ShotSettings& settings, const std::string& file,
                        Diagnostics& diagnostics) {
  if (size_t(node.camera) >= model.cameras.size())
    throw_input(file, path + ".camera",
                out_of_range("camera", node.camera, model.cameras.size(), "cameras"));
  const tinygltf::Camera& g = model.cameras[size_t(node.camera)];
  const std::string cpath = index_path("cameras", size_t(node.camera));
  SceneCamera camera;
  camera.name = !g.name.empty() ? g.name : !node.name.empty() ? node.name : cpath;
  camera.source = path + " (" + cpath + ")";
  camera.node_index = scene_node;
  // Blender ignores camera scale when projecting: keep rotation and position only.
  camera.world_from_camera = world.without_scale();
  if (!camera.world_from_camera.is_finite())
    throw_input(file, path, "the camera's transform is degenerate (zero scale?)");
  read_core_projection(g, cpath, file, camera);
  if (settings.width_px) camera.intended_aspect = double(*settings.width_px) / *settings.height_px;

  // Lowest precedence first, so that each source overrides what the ones below it name.
  PhysicalCamera& phys = camera.physical;
  const PhysicalCamera from_yfov = phys;
  std::string used;
  const Fields extras(g.extras, cpath + ".extras", file);
  if (apply_camera_fields(extras, phys)) used = "extras";
  bool fit_named = extras.has("sensor_fit");
  if (const tinygltf::Value* ext = extension(g, "EXT_camera_physical"))
    if (apply_ext_camera_physical(Fields(*ext, cpath + ".extensions.EXT_camera_physical", file),
                                  phys))
      used = "EXT_camera_physical";
  std::optional<FocusTrack> track = read_focus_track(extras);
  if (const tinygltf::Value* ext = extension(g, "FILMBACK_blender")) {
    const Fields ours(*ext, cpath + ".extensions.FILMBACK_blender", file);
    if (apply_camera_fields(ours, phys)) used = "FILMBACK_blender";
    fit_named |= ours.has("sensor_fit");
    if (auto t = read_focus_track(ours)) track = std::move(t);
  }
  camera.focus_track = std::move(track);
  if (used.empty() || g.type != "perspective" || !camera.intended_aspect) return camera;

  const double aspect = *camera.intended_aspect;
  const double yfov = vertical_fov_deg(from_yfov, aspect);
  if (used == "EXT_camera_physical" && !fit_named && !fit_to_yfov(phys, yfov, aspect)) {
    // The draft keeps the core projection authoritative.
    diagnostics.warn(located(file, cpath,
                             "EXT_camera_physical's focal length and sensor give yfov under no "
                             "sensor fit; using yfov (" +
                                 number_text(yfov) + " deg)"));
    phys = from_yfov;
    return camera;
  }
  const double physical = vertical_fov_deg(phys, aspect);
  if (std::abs(yfov - physical) > kFovToleranceDeg)
    diagnostics.warn(located(file, cpath,
                             "yfov gives a vertical field of view of " + number_text(yfov) +
                                 " deg, the physical camera in " + used + " " +
                                 number_text(physical) + " deg; using " + used));
  return camera;
}

}  // namespace fb::gltf
