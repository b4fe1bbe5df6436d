#include "importers/gltf/gltf_camera.h"

#include <tiny_gltf.h>

#include <filmback/camera_projection.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/util/error.h"
#include "importers/gltf/gltf_camera_panorama.h"
#include "importers/gltf/gltf_camera_source.h"
#include "importers/gltf/gltf_json.h"
#include "importers/gltf/gltf_lens_distortion.h"

namespace fb::gltf {
namespace {

using V = CameraValue;

// Bounds on camera shapes, far beyond any real shot, so that no camera reaches the renderer with a
// view plane that float arithmetic cannot trace.
constexpr double kMinAspect = 1e-4;
constexpr double kMaxMagnification = 1e9;  // m

// Two descriptions of one shot agree when their vertical fields of view differ by at most this.
constexpr double kFovToleranceDeg = 0.01;

// The image shape yfov is reproduced at when neither the camera nor the scene gives one: the
// render's default (docs/cli.md, "--res").
constexpr double kDefaultAspect = 16.0 / 9.0;

double vertical_fov_deg(const PhysicalCamera& camera, double aspect) {
  constexpr uint32_t kHeight = 100000;
  const auto width = uint32_t(std::max(1.0, std::round(aspect * kHeight)));
  return describe_camera(camera, width, kHeight).vertical_fov_deg;
}

// The focal length under which the camera's sensor and fit give yfov at this image shape: the
// fitted side spans sensor / f at unit depth, the vertical side that over the aspect when the fit
// is horizontal (view_plane, core/sdk/filmback/camera_projection.h; the image shape goes in as a
// 1 x 1 image's pixel aspect).
double focal_for_yfov(const PhysicalCamera& camera, double yfov_rad, double aspect) {
  const fb_camera_setup setup = make_camera_setup(camera, 1, 1, aspect);
  const double tan_half_y = std::tan(yfov_rad / 2);
  return fitted_sensor_mm(setup) /
         (2 * (fits_horizontally(setup) ? tan_half_y * aspect : tan_half_y));
}

void set(SceneCamera& camera, V v, double x, ValueOrigin origin) {
  set_camera_value(camera.physical, v, x);
  camera.origins[size_t(v)] = std::move(origin);
}

// The core projection as Blender's physical set (docs/camera-model.md); every other value keeps
// Blender's default.
void read_core_projection(const tinygltf::Camera& g, const std::string& cpath,
                          const std::string& file, SceneCamera& camera) {
  camera.origins.fill(ValueOrigin::by_default("Blender's; no source names it"));
  camera.origins[size_t(V::kFstop)] = ValueOrigin::by_default("no source names it: a pinhole");
  const auto at = [&](const std::string& path, std::string how = {}) {
    return ValueOrigin::from_file(file, cpath + path, std::move(how));
  };
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
    camera.physical.projection = FB_PROJECTION_PERSPECTIVE;
    // With an aspect ratio, a 36 mm sensor with AUTO fit, whose fitted side spans the larger
    // image side; without one, the vertical field of view is kept for any image shape.
    if (p.aspectRatio > 0) {
      camera.intended_aspect = p.aspectRatio;
    } else {
      set(camera, V::kSensorFit, FB_SENSOR_FIT_VERTICAL,
          at(".perspective", "no aspectRatio: yfov is kept for any image shape"));
    }
    camera.physical.focal_length_mm =
        focal_for_yfov(camera.physical, p.yfov, camera.intended_aspect.value_or(kDefaultAspect));
    camera.origins[size_t(V::kFocalLength)] =
        at(".perspective.yfov", "under the sensor and its fit");
    set(camera, V::kClipNear, p.znear, at(".perspective.znear"));
    if (p.zfar > 0)
      set(camera, V::kClipFar, p.zfar, at(".perspective.zfar"));
    else  // an infinite projection
      set(camera, V::kClipFar, HUGE_VAL, at(".perspective", "no zfar: infinite"));
  } else if (g.type == "orthographic") {
    const tinygltf::OrthographicCamera& o = g.orthographic;
    if (!(o.xmag > 0 && o.xmag <= kMaxMagnification && o.ymag > 0 && o.ymag <= kMaxMagnification &&
          o.xmag / o.ymag >= kMinAspect && o.xmag / o.ymag <= 1 / kMinAspect))
      throw_input(file, cpath + ".orthographic",
                  "expected xmag and ymag in (0, 1e9] m with a ratio from 1e-4 to 1e4");
    if (!(o.zfar > o.znear) || o.znear < 0)
      throw_input(file, cpath + ".orthographic", "expected 0 <= znear < zfar");
    camera.physical.projection = FB_PROJECTION_ORTHOGRAPHIC;
    // Blender: xmag = scale * w / max(w, h) / 2
    set(camera, V::kOrthoScale, 2 * std::max(o.xmag, o.ymag),
        at(".orthographic", "2 max(xmag, ymag)"));
    camera.intended_aspect = o.xmag / o.ymag;
    set(camera, V::kClipNear, o.znear, at(".orthographic.znear"));
    set(camera, V::kClipFar, o.zfar, at(".orthographic.zfar"));
  } else {
    throw_input(file, cpath + ".type",
                "'" + g.type + "' is not a camera type (expected perspective or orthographic)");
  }
}

const tinygltf::Value* extension(const tinygltf::Camera& g, const char* name) {
  const auto it = g.extensions.find(name);
  return it == g.extensions.end() ? nullptr : &it->second;
}

// The sources that describe this camera, highest first.
std::vector<CameraSource> camera_sources(const tinygltf::Camera& g, const std::string& cpath,
                                         const std::string& file) {
  std::vector<CameraSource> sources;
  if (const tinygltf::Value* ext = extension(g, "FILMBACK_blender"))
    sources.push_back(read_blender_camera_fields(
        Fields(*ext, cpath + ".extensions.FILMBACK_blender", file), "FILMBACK_blender"));
  if (const tinygltf::Value* ext = extension(g, "EXT_camera_physical"))
    sources.push_back(
        read_ext_camera_physical(Fields(*ext, cpath + ".extensions.EXT_camera_physical", file)));
  sources.push_back(
      read_blender_camera_fields(Fields(g.extras, cpath + ".extras", file), "extras"));
  std::erase_if(sources, [](const CameraSource& s) { return !s.names_any(); });
  return sources;
}

// Each value from the highest source that can express it: what that source names, else what its
// absence means (Blender's default: no depth of field, no shift) or, for the projection's values
// it leaves out, the core projection's. A lower source that names the value differently is
// ignored, and said so. Returns, per value, the source that decided it (null: none).
std::array<const CameraSource*, kCameraValueCount> take_sources_whole(
    const std::vector<CameraSource>& sources, const std::string& file, SceneCamera& camera,
    Diagnostics& diagnostics) {
  std::array<const CameraSource*, kCameraValueCount> decided{};
  std::vector<std::string> ignored(sources.size());
  for (size_t v = 0; v < kCameraValueCount; ++v) {
    for (const CameraSource& s : sources) {
      if (!s.expresses[v]) continue;
      if (!decided[v]) {
        decided[v] = &s;
        if (s.values[v])
          set(camera, V(v), *s.values[v], ValueOrigin::from_file(file, s.paths[v]));
        else if (camera.origins[v].file.empty())
          camera.origins[v].how =
              s.name + " names none: " +
              (V(v) == V::kFstop ? "depth of field off, a pinhole" : "Blender's default");
      } else if (s.values[v] && *s.values[v] != camera_value(camera.physical, V(v))) {
        ignored[size_t(&s - sources.data())] +=
            std::string(ignored[size_t(&s - sources.data())].empty() ? "" : ", ") +
            camera_value_name(V(v));
      }
    }
  }
  for (size_t i = 0; i < sources.size(); ++i)
    if (!ignored[i].empty())
      diagnostics.warn(located(file, sources[i].path,
                               ignored[i] + " ignored: " + sources.front().name +
                                   " describes the camera (docs/blender.md, \"Cameras\")"));
  // Each tracked value from the track of the source that decided it.
  for (V v : LensTrack::kTracked) {
    const CameraSource* s = decided[size_t(v)];
    if (!s || !s->lens_track || !s->lens_track->tracks(v)) continue;
    if (!camera.lens_track) camera.lens_track = LensTrack{s->lens_track->first_frame, {}};
    camera.lens_track->values[size_t(v)] = s->lens_track->values[size_t(v)];
    camera.origins[size_t(v)] =
        ValueOrigin::from_file(file, s->track_paths[size_t(v)], "at the rendered frame");
  }
  return decided;
}

bool named(const std::array<const CameraSource*, kCameraValueCount>& decided, V v) {
  const CameraSource* s = decided[size_t(v)];
  return s && s->values[size_t(v)];
}

// EXT_camera_physical has no sensor fit, nor do extras that leave it out: take the one under which
// the focal length and sensor give the file's yfov (AUTO, then horizontal, then vertical). False
// when none does (the fit is left AUTO).
bool fit_to_yfov(PhysicalCamera& phys, double yfov_deg, double aspect) {
  for (uint32_t fit : {FB_SENSOR_FIT_AUTO, FB_SENSOR_FIT_HORIZONTAL, FB_SENSOR_FIT_VERTICAL}) {
    phys.sensor_fit = fit;
    if (std::abs(vertical_fov_deg(phys, aspect) - yfov_deg) <= kFovToleranceDeg) return true;
  }
  phys.sensor_fit = FB_SENSOR_FIT_AUTO;
  return false;
}

// What the sources leave to yfov: the focal length (under their sensor and fit, never under the
// core's 36 mm assumption) or the sensor fit; then the 0.01 degree agreement check.
void agree_with_yfov(const tinygltf::Camera& g, const std::string& cpath, const std::string& file,
                     const std::array<const CameraSource*, kCameraValueCount>& decided,
                     const SceneCamera& core, SceneCamera& camera, Diagnostics& diagnostics) {
  PhysicalCamera& phys = camera.physical;
  const double aspect = camera.intended_aspect.value_or(kDefaultAspect);
  const double yfov_deg = g.perspective.yfov * 180 / std::numbers::pi;
  const std::string yfov_path = cpath + ".perspective.yfov";
  const std::string shape = camera.intended_aspect ? "" : " at 16:9, the default image shape";
  const bool focal_named = named(decided, V::kFocalLength);
  if (!focal_named) {
    phys.focal_length_mm = focal_for_yfov(phys, g.perspective.yfov, aspect);
    camera.origins[size_t(V::kFocalLength)] =
        ValueOrigin::from_file(file, yfov_path, "under the sensor and its fit" + shape);
    return;
  }
  const CameraSource& source = *decided[size_t(V::kFocalLength)];
  if (!named(decided, V::kSensorFit)) {
    if (fit_to_yfov(phys, yfov_deg, aspect)) {
      camera.origins[size_t(V::kSensorFit)] = ValueOrigin::from_file(
          file, yfov_path, "the fit under which " + source.name + "'s lens gives yfov" + shape);
    } else if (source.name == "EXT_camera_physical") {
      // The draft keeps the core projection authoritative.
      diagnostics.warn(located(file, cpath,
                               "EXT_camera_physical's focal length and sensor give yfov under no "
                               "sensor fit; using yfov (" +
                                   number_text(yfov_deg) + " deg)"));
      for (V v : {V::kFocalLength, V::kSensorWidth, V::kSensorHeight, V::kSensorFit})
        set(camera, v, camera_value(core.physical, v), core.origin(v));
      return;
    }
  }
  const double physical = vertical_fov_deg(phys, aspect);
  if (std::abs(yfov_deg - physical) > kFovToleranceDeg)
    diagnostics.warn(located(file, cpath,
                             "yfov gives a vertical field of view of " + number_text(yfov_deg) +
                                 " deg, the physical camera in " + source.name + " " +
                                 number_text(physical) + " deg; using " + source.name));
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

  const SceneCamera core = camera;
  const std::vector<CameraSource> sources = camera_sources(g, cpath, file);
  const auto decided = take_sources_whole(sources, file, camera, diagnostics);
  const PhysicalCamera& phys = camera.physical;
  if (!(phys.clip_far_m > phys.clip_near_m))
    camera.origin(V::kClipFar)
        .fail("expected clip_far_m > clip_near_m (" + number_text(phys.clip_near_m) + " m at " +
              camera.origin(V::kClipNear).text() + ")");
  if (const tinygltf::Value* ext = extension(g, "FILMBACK_blender")) {
    // A panorama's core camera is a perspective stand-in for other viewers: no yfov to agree with.
    camera.model = read_panorama(*ext, cpath + ".extensions.FILMBACK_blender", file);
    if (camera.model) {
      camera.physical.projection = FB_PROJECTION_PANORAMIC;
      return camera;
    }
  }
  if (!sources.empty() && g.type == "perspective")
    agree_with_yfov(g, cpath, file, decided, core, camera, diagnostics);
  if (const tinygltf::Value* ext = extension(g, "FILMBACK_blender"))
    camera.lens_distortion =
        read_lens_distortion(Fields(*ext, cpath + ".extensions.FILMBACK_blender", file));
  return camera;
}

}  // namespace fb::gltf
