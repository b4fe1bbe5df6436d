#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <utility>

#include "core/cmd/commands.h"
#include "core/render/plugin_choice_loader.h"
#include "core/render/shot_plan.h"
#include "core/scene/camera.h"
#include "importers/import_scene.h"

namespace fb {
namespace {

std::string format(const char* fmt, auto... args) {
  char text[512];
  std::snprintf(text, sizeof text, fmt, args...);
  return text;
}

std::string rgb(Rgb c) {
  return format("(%.4g, %.4g, %.4g)", c.x, c.y, c.z);
}
std::string point(Vec3d p) {
  return format("(%.6g, %.6g, %.6g)", p.x, p.y, p.z);
}

// Cycles' names (Film > Pixel Filter).
const char* pixel_filter_name(PixelFilterSetting::Type type) {
  switch (type) {
    case PixelFilterSetting::Type::kGaussian:
      return "GAUSSIAN";
    case PixelFilterSetting::Type::kBox:
      return "BOX";
    case PixelFilterSetting::Type::kBlackmanHarris:
      break;
  }
  return "BLACKMAN_HARRIS";
}

// Where each value came from (docs/blender.md, "Cameras"): one line per value.
void print_origins(const SceneCamera& camera) {
  std::cout << "    from:\n";
  for (size_t v = 0; v < kCameraValueCount; ++v)
    std::cout << "      " << camera_value_name(CameraValue(v)) << ": " << camera.origins[v].text()
              << '\n';
}

const char* projection_name(uint32_t projection) {
  return projection == FB_PROJECTION_ORTHOGRAPHIC ? "orthographic"
         : projection == FB_PROJECTION_PANORAMIC  ? "panoramic"
                                                  : "perspective";
}

// A projection of the scene's own (docs/camera-model.md, "Panoramic cameras"): its kind and each
// value exactly, with where it came from; the plugin's defaults (Blender's) fill the others.
void print_model(const CameraModel& model) {
  std::cout << "    projection " << model.kind << " (" << model.origin.text() << ")\n";
  for (const NamedNumber& n : model.numbers)
    std::cout << format("      %s=%.17g (%s)\n", n.key.c_str(), n.value, n.origin.text().c_str());
}

void print_camera(const SceneCamera& camera, const ShotSettings& shot) {
  const PhysicalCamera& c = camera.physical;
  const auto [width, height] =
      shot.width_px ? std::pair{*shot.width_px, *shot.height_px} : default_resolution(camera);
  const CameraQuantities q = describe_camera(c, width, height);
  const bool ortho = c.projection == FB_PROJECTION_ORTHOGRAPHIC;
  // the sensor side that spans the image
  const char* fitted =
      sensor_fit_name(q.horizontal_fit ? FB_SENSOR_FIT_HORIZONTAL : FB_SENSOR_FIT_VERTICAL);
  std::cout << "  " << camera.name << "  [" << camera.source << "]  "
            << (camera.model ? camera.model->kind : projection_name(c.projection)) << '\n';
  if (camera.model) {
    // The lens and sensor as the scene has them (Cycles' equisolid and polynomial fisheyes use the
    // sensor, an aperture the focal length); the field of view is the projection's own, which its
    // plugin derives under the plan.
    std::cout << format(
        "    focal length %.3f mm, sensor %.2f x %.2f mm, fit %s (%s at %ux%u), shift %.4g, %.4g\n",
        c.focal_length_mm, c.sensor_width_mm, c.sensor_height_mm, sensor_fit_name(c.sensor_fit),
        fitted, width, height, c.shift_x, c.shift_y);
    print_model(*camera.model);
    std::cout << "    field of view: the projection's, as its camera model says under the plan\n";
  } else if (ortho) {
    std::cout << format("    ortho scale %.6g m, sensor fit %s (%s at %ux%u)\n", c.ortho_scale_m,
                        sensor_fit_name(c.sensor_fit), fitted, width, height);
  } else {
    std::cout << format(
        "    focal length %.3f mm, sensor %.2f x %.2f mm, fit %s (%s at %ux%u), shift %.4g, %.4g\n",
        c.focal_length_mm, c.sensor_width_mm, c.sensor_height_mm, sensor_fit_name(c.sensor_fit),
        fitted, width, height, c.shift_x, c.shift_y);
    std::cout << format(
        "    field of view %.4f deg horizontal x %.4f deg vertical (imaged sensor area %.2f x %.2f "
        "mm)\n",
        q.horizontal_fov_deg, q.vertical_fov_deg, q.imaged_sensor_width_mm,
        q.imaged_sensor_height_mm);
    std::cout << format(
        "    35 mm equivalent focal length: %.2f mm (width-based, 36 mm), %.2f mm (diagonal-based, "
        "43.27 mm)\n",
        q.equivalent_35mm_width_mm, q.equivalent_35mm_diagonal_mm);
  }
  if (c.has_aperture())
    std::cout << format(
        "    aperture f/%.4g (%.4g mm across), focused at %s, %s, ratio %.4g\n", c.fstop,
        c.focal_length_mm / c.fstop,
        std::isinf(c.focus_distance_m) ? "infinity" : format("%.6g m", c.focus_distance_m).c_str(),
        c.aperture_blades ? format("%u blades rotated %.4g deg", c.aperture_blades,
                                   c.aperture_rotation_rad * 180 / M_PI)
                                .c_str()
                          : "round",
        c.aperture_ratio);
  else if (!ortho && !camera.model)
    std::cout << "    pinhole (no aperture: everything in focus)\n";
  std::cout << format(
      "    clip %.6g m to %s, at %s m\n", c.clip_near_m,
      std::isinf(c.clip_far_m) ? "infinity" : format("%.6g m", c.clip_far_m).c_str(),
      point(camera.world_from_camera.translation()).c_str());
  if (const std::optional<LensTrack>& track = camera.lens_track)
    for (CameraValue v : LensTrack::kTracked)
      if (const size_t n = track->values[size_t(v)].size())
        std::cout << format("    %s varies over frames %.17g to %.17g (%zu values)\n",
                            camera_value_name(v), track->first_frame,
                            track->first_frame + double(n - 1), n);
  // Every value exactly as imported (%.17g round-trips a double), under the names of the
  // FILMBACK_blender extension, for scripts: docs/blender.md, "Cameras".
  std::cout << "    exact: projection=" << projection_name(c.projection)
            << format(" focal_length_mm=%.17g sensor_width_mm=%.17g sensor_height_mm=%.17g",
                      c.focal_length_mm, c.sensor_width_mm, c.sensor_height_mm)
            << " sensor_fit=" << sensor_fit_name(c.sensor_fit)
            << format(
                   " shift_x=%.17g shift_y=%.17g ortho_scale_m=%.17g clip_near_m=%.17g"
                   " clip_far_m=%.17g fstop=%.17g focus_distance_m=%.17g aperture_blades=%u"
                   " aperture_rotation_rad=%.17g aperture_ratio=%.17g\n",
                   c.shift_x, c.shift_y, c.ortho_scale_m, c.clip_near_m, c.clip_far_m, c.fstop,
                   c.focus_distance_m, c.aperture_blades, c.aperture_rotation_rad,
                   c.aperture_ratio);
  print_origins(camera);
}

void print_shot(const ShotSettings& s) {
  std::cout << "shot";
  if (s.width_px) std::cout << format(" %ux%u px", *s.width_px, *s.height_px);
  if (s.pixel_aspect) std::cout << format(", pixel aspect %.6g", *s.pixel_aspect);
  if (s.fps) std::cout << format(", %.6g fps", *s.fps);
  if (s.frame) std::cout << format(", frame %.6g", *s.frame);
  if (s.shutter_open_s)
    std::cout << format(", shutter %.6g s to %.6g s%s", *s.shutter_open_s, *s.shutter_close_s,
                        s.shutter_curve.empty() ? "" : " with a curve");
  if (s.rolling_shutter_duration)
    std::cout << format(", rolling shutter top to bottom, each row %.6g of it",
                        *s.rolling_shutter_duration);
  if (s.filter)
    std::cout << ", filter " << pixel_filter_name(s.filter->type)
              << format(" %.6g px wide (%s)", s.filter->width_px, s.filter->origin.text().c_str());
  if (s.film_exposure != 1.0) std::cout << format(", film exposure x%.6g", s.film_exposure);
  std::cout << '\n';
  const ViewSettings& v = s.view;
  if (v.names_view())
    std::cout << "  view (8-bit outputs): display '" << v.display_device << "', view '"
              << v.view_transform << "', look '" << v.look << "'"
              << format(", exposure %.6g stops, gamma %.6g, dither %.6g\n", v.exposure_stops,
                        v.gamma, v.dither_intensity);
  else
    std::cout << "  view (8-bit outputs): the plain sRGB curve"
              << format(", exposure %.6g stops, gamma %.6g, dither %.6g\n", v.exposure_stops,
                        v.gamma, v.dither_intensity);
}

const char* light_type(LightType t) {
  switch (t) {
    case LightType::kPoint:
      return "point";
    case LightType::kSpot:
      return "spot";
    case LightType::kDirectional:
      return "directional";
    case LightType::kArea:
      return "area";
  }
  return "?";
}

// What Light::intensity is for a light of type t, and its unit.
std::pair<const char*, const char*> light_quantity(LightType t) {
  switch (t) {
    case LightType::kDirectional:
      return {"irradiance", "W/m^2"};
    case LightType::kArea:
      return {"radiance", "W/sr/m^2"};
    default:
      return {"intensity", "W/sr"};
  }
}

// What the planned camera plugin derives from its values (fb_camera_api::describe): a panorama's
// field of view, a lens' focal length and pupil. Loading it also proves the plan renders; when
// the user named the plugin (--camera-model), its failure is theirs to see as an error.
void print_camera_description(const ShotPlan& plan, bool typed) {
  try {
    const PluginLoader loader(PluginLoader::default_search_dirs());
    const std::string lines = load_camera(loader, plan)->describe();
    if (lines.empty()) return;
    std::cout << "  camera model " << plan.camera_model.name << " says:\n";
    std::istringstream in(lines);
    for (std::string line; std::getline(in, line);)
      std::cout << "    " << line << '\n';
  } catch (const std::runtime_error& e) {  // a plugin missing or refusing the shot's values
    if (typed) throw;
    std::cout << "  camera model " << plan.camera_model.name << " cannot start: " << e.what()
              << '\n';
  }
}

}  // namespace

// What `filmback render` chooses with no other option: the shot plan (core/render/shot_plan.h),
// each plugin with why it was chosen and each value it is handed with where that came from. A shot
// no plugin can render says why instead.
void print_plan(const Scene& scene, const std::optional<std::string>& camera,
                const std::optional<std::string>& camera_model) {
  RenderOptions options;
  options.camera = camera;
  options.camera_model = camera_model;
  std::cout << "plan (filmback render "
            << (camera_model ? "--camera-model " + *camera_model : std::string("without options"))
            << ")";
  try {
    const ShotPlan plan = plan_shot(scene, options);
    std::cout << format(": camera '%s', %ux%u, %u spp\n", plan.camera.name.c_str(), plan.width_px,
                        plan.height_px, plan.samples_per_pixel);
    for (const auto& [kind, choice] : {std::pair{"camera model", &plan.camera_model},
                                       {"filter", &plan.filter},
                                       {"integrator", &plan.integrator}}) {
      std::cout << "  " << kind << " " << choice->name << "  (" << choice->origin.text() << ")\n";
      for (const NamedNumber& n : choice->numbers)
        std::cout << "    " << n.key << format(" = %.17g", n.value) << "  from " << n.origin.text()
                  << '\n';
    }
    print_camera_description(plan, camera_model.has_value());
  } catch (const std::runtime_error& e) {  // InputError or UsageError: the scene as it stands
    if (camera_model) throw;
    std::cout << ": cannot render: " << e.what() << '\n';
  }
}

int run_info(const std::filesystem::path& file, const ImportOptions& options,
             const std::optional<std::string>& only_camera,
             const std::optional<std::string>& camera_model) {
  Diagnostics diagnostics;
  const Scene scene = import_scene(file, options, diagnostics);
  diagnostics.print(std::cerr);
  if (only_camera) {
    print_camera(find_camera(scene, *only_camera), scene.settings);
    print_plan(scene, only_camera, camera_model);
    return 0;
  }
  std::cout << "scene " << file.string() << '\n';
  print_shot(scene.settings);

  std::cout << "cameras (" << scene.cameras.size() << ")"
            << (scene.cameras.empty()
                    ? ": none; a render frames the scene bounds with the default camera"
                    : "")
            << '\n';
  for (const SceneCamera& camera : scene.cameras)
    print_camera(camera, scene.settings);

  std::cout << "lights (" << scene.lights.size() << ")\n";
  for (const Light& light : scene.lights) {
    const bool area = light.type == LightType::kArea;
    const auto [quantity, unit] = light_quantity(light.type);
    std::cout << "  " << light.name << "  " << light_type(light.type) << ", " << quantity << " "
              << rgb(light.intensity) << " " << unit;
    if (area)
      std::cout << format(", %s %.4g x %.4g m, spread %.4g deg",
                          light.area_shape == AreaShape::kEllipse ? "ellipse" : "rectangle",
                          light.size_x_m, light.size_y_m, light.spread_rad * 180 / M_PI);
    if (light.type == LightType::kSpot)
      std::cout << format(", cone %.2f..%.2f deg", light.spot_inner_angle_rad * 180 / M_PI,
                          light.spot_outer_angle_rad * 180 / M_PI);
    std::cout << ", at " << point(light.world_from_light.translation()) << " m\n";
  }

  std::map<uint32_t, size_t> uses;
  for (const MeshInstance& instance : scene.instances)
    ++uses[instance.mesh];
  std::cout << "meshes (" << scene.meshes.size() << " meshes, " << scene.instances.size()
            << " instances, " << scene.triangle_count() << " triangles rendered)\n";
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const TriangleMesh& m = scene.meshes[i];
    std::cout << "  " << m.name << "  " << m.triangle_count() << " triangles, "
              << m.positions.size() << " vertices" << (m.normals.empty() ? "" : " with normals")
              << ", material '" << scene.materials[m.material].name << "', " << uses[uint32_t(i)]
              << " instance(s)\n";
  }
  // Which path each deformed mesh takes (docs/scenes.md, "Skins and morph targets", "Blender's
  // evaluated deformation").
  if (!scene.deformations.empty())
    std::cout << "deformed meshes (" << scene.deformations.size() << ")\n";
  for (const MeshDeformation& d : scene.deformations) {
    std::cout << "  " << scene.meshes[d.mesh].name << "  ";
    const std::vector<double>& times = d.evaluated.times_s;
    if (times.size() == 1)
      std::cout << "evaluated shape at " << number_text(times[0]) << " s from the frame\n";
    else if (!times.empty())
      std::cout << "evaluated shapes at " << times.size() << " times, "
                << number_text(times.front()) << " to " << number_text(times.back())
                << " s from the frame\n";
    else
      std::cout << (d.skin
                        ? "glTF skin of " + std::to_string(d.skin->joint_nodes.size()) + " joints"
                        : std::string("glTF morph targets"))
                << (d.skin && !d.morph.empty() ? " after morph targets" : "") << "\n";
  }
  if (!scene.subdivision_surfaces.empty())
    std::cout << "subdivision surfaces (" << scene.subdivision_surfaces.size()
              << ", refined when rendered: docs/blender.md)\n";
  for (const SubdivisionSurface& s : scene.subdivision_surfaces) {
    std::cout << "  " << s.name << "  cage of " << s.cage_face_sizes.size() << " faces, "
              << s.cage_positions.size() << " vertices, " << s.edge_creases.size()
              << " creased edges; "
              << (s.settings.scheme == SubdivisionSettings::Scheme::kSimple ? "simple"
                                                                            : "Catmull-Clark")
              << " level " << s.settings.levels_render << ", material"
              << (s.parts.size() > 1 ? "s" : "");
    for (size_t p = 0; p < s.parts.size(); ++p)
      std::cout << (p ? ", '" : " '") << scene.materials[s.parts[p].material].name << "'";
    if (!s.uv_maps.empty()) {
      std::cout << "; UV maps";
      for (size_t m = 0; m < s.uv_maps.size(); ++m)
        std::cout << (m ? ", '" : " '") << s.uv_maps[m].name << "'";
    }
    std::cout << '\n';
  }

  std::cout << "materials (" << scene.materials.size() << ")\n";
  for (const Material& m : scene.materials)
    std::cout << "  " << m.name << "  base colour " << rgb(m.base_color) << ", emission "
              << rgb(m.emission) << " W/sr/m^2" << (m.double_sided ? ", double-sided" : "") << '\n';
  print_plan(scene, std::nullopt, camera_model);
  return 0;
}

}  // namespace fb
