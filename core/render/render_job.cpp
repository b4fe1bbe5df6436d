#include "core/render/render_job.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

#include <filmback/camera_projection.h>

#include "core/accel/render_geometry.h"
#include "core/film/splat_tiles.h"
#include "core/plugin/instances.h"
#include "core/plugin/params.h"
#include "core/render/light_sampler.h"
#include "core/render/memory_estimate.h"
#include "core/render/motion.h"
#include "core/render/shutter.h"
#include "core/render/trace_context.h"
#include "core/scene/default_camera.h"
#include "core/subdiv/refine_scene.h"
#include "core/util/error.h"

namespace fb {

struct RenderJob::Plugins {
  Transform render_from_world;
  std::unique_ptr<CameraInstance> camera;
  std::unique_ptr<FilterInstance> filter;
  std::unique_ptr<IntegratorInstance> integrator;
  std::string filter_text, integrator_text;
  std::unique_ptr<RenderGeometry> geometry;
  std::unique_ptr<LightSampler> lights;
  ShutterCurve shutter_curve;
  TimeSampling time;
  std::unique_ptr<CameraPath> camera_path;
  std::unique_ptr<Scene> refined;  // the scene with its subdivision surfaces made triangles
  std::string subdiv_summary;
  std::vector<fb_material> materials;
  fb_scene_api scene_api{};  // host_scene_api(), as long as the integrator knows it
  fb_scene scene{};
};

namespace {

// The named camera (else the first, else one framing the scene), placed where it is at time_s.
SceneCamera choose_camera(const Scene& scene, const std::optional<std::string>& name,
                          double time_s) {
  const auto posed = [&](SceneCamera camera) {
    camera.world_from_camera = scene.world_from_camera(camera, time_s);
    if (!camera.world_from_camera.is_finite())  // an animated scale of 0, say
      throw InputError(scene.file.string() + ": camera '" + camera.name +
                       "' at t = " + number_text(time_s) + " s: its transform is degenerate");
    return camera;
  };
  if (!name)
    return scene.cameras.empty() ? frame_bounds(scene.world_bounds(time_s))
                                 : posed(scene.cameras.front());
  return posed(find_camera(scene, *name));
}

// The shutter curve: --shutter-curve, else the shot's sampled curve as it is (typed, never
// printed and parsed), else a box. An error names where the curve came from.
ShutterCurve shutter_curve(const std::optional<std::string>& typed, const ShotSettings& shot) {
  if (typed) return ShutterCurve::parse(*typed, "--shutter-curve");
  const std::vector<double>& values = shot.shutter_curve;
  if (std::adjacent_find(values.begin(), values.end(), std::not_equal_to<>()) == values.end())
    return ShutterCurve();  // empty or constant: a box
  if (std::optional<ShutterCurve> curve = ShutterCurve::table(values)) return std::move(*curve);
  shot.shutter_curve_origin.fail(ShutterCurve::kTableExpected);
}

// A plugin and number parameters chosen from typed scene data.
struct TypedPlugin {
  const char* name;
  std::vector<std::pair<const char*, double>> numbers;
};

// Cycles' pixel filters as filter plugins (docs/filters.md, "Against Blender"): Blackman-Harris of
// width w spans +-w; the Gaussian of width w is exp(-8x^2/w^2) (sigma = w/4) cut at +-1.5w; the box
// of width w spans +-w/2.
TypedPlugin filter_plugin_for(const PixelFilterSetting& filter) {
  const double w = filter.width_px;
  switch (filter.type) {
    case PixelFilterSetting::Type::kGaussian:
      return {"gaussian", {{"radius", 1.5 * w}, {"sigma", w / 4}}};
    case PixelFilterSetting::Type::kBox:
      return {"box", {{"radius", w / 2}}};
    case PixelFilterSetting::Type::kBlackmanHarris:
      break;
  }
  return {"blackman_harris", {{"width", w}}};
}

// "gaussian:radius=2.25,sigma=0.375": for the plan line and the image metadata only.
std::string plugin_text(const TypedPlugin& plugin) {
  std::string text = plugin.name;
  for (size_t i = 0; i < plugin.numbers.size(); ++i) {
    text.append(i ? "," : ":").append(plugin.numbers[i].first).append("=");
    text.append(number_text(plugin.numbers[i].second));
  }
  return text;
}

ImageMetadata::Matrix to_float_matrix(const Transform& t) {
  ImageMetadata::Matrix m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      m[r * 4 + c] = float(t(r, c));
  return m;
}

// OpenEXR's NDC: (0,0) at the top-left corner of the image, (1,1) at the bottom-right.
Transform ndc_from_camera(const fb_camera_setup& setup) {
  const ViewPlane v = view_plane(setup);
  const double w = setup.image_width_px, h = setup.image_height_px;
  if (setup.projection == FB_PROJECTION_ORTHOGRAPHIC)
    return Transform::from_rows({v.fx / w, 0, 0, v.cx / w,   //
                                 0, -v.fy / h, 0, v.cy / h,  //
                                 0, 0, 1, 0,                 //
                                 0, 0, 0, 1});
  // x_ndc = (cx + fx X / -Z) / w, with the division by -Z done by the homogeneous w
  return Transform::from_rows({v.fx / w, 0, -v.cx / w, 0,   //
                               0, -v.fy / h, -v.cy / h, 0,  //
                               0, 0, -1, 0,                 //
                               0, 0, -1, 0});
}

// Loads the plugin `text` names ("NAME[:k=v,...]") and creates an instance with its parameters;
// usage errors say which option they came from.
template <typename Instance, typename... Setup>
std::unique_ptr<Instance> instantiate(const PluginLoader& loader, uint32_t kind,
                                      const std::string& text, const char* option,
                                      const Setup&... setup) {
  const PluginSpec spec = parse_plugin_spec(text, option);
  auto library = loader.load(kind, spec.name);
  try {
    return std::make_unique<Instance>(library, BoundParams(library->descriptor(), spec.settings),
                                      setup...);
  } catch (const UsageError& e) {
    throw UsageError(std::string(option) + " '" + text + "': " + e.what());
  }
}

// Loads `plugin` and creates an instance with its typed values; an error names `origin`, where the
// values came from (a scene's file and JSON path: bad input).
template <typename Instance>
std::unique_ptr<Instance> instantiate(const PluginLoader& loader, uint32_t kind,
                                      const TypedPlugin& plugin, const ValueOrigin& origin) {
  auto library = loader.load(kind, plugin.name);
  BoundParams params(library->descriptor(), {});
  for (const auto& [key, x] : plugin.numbers)
    if (std::string expected = params.set_number(library->descriptor(), key, x); !expected.empty())
      origin.fail("the plugin " + plugin_text(plugin) + ": parameter '" + key +
                  "' = " + number_text(x) + ": expected " + expected);
  try {
    return std::make_unique<Instance>(library, params);
  } catch (const UsageError& e) {
    origin.fail("the plugin " + plugin_text(plugin) + ": " + e.what());
  }
}

// Only what the shot needs: a pinhole unless it has an aperture (docs/camera-model.md).
std::string camera_model_for(const PhysicalCamera& camera, const SensorResponse& sensor) {
  if (camera.projection == FB_PROJECTION_ORTHOGRAPHIC) {
    if (sensor.model == FB_SENSOR_PHYSICAL)
      throw UsageError(
          "--sensor-model physical: an orthographic camera has no aperture to expose through");
    return "orthographic";
  }
  if (camera.has_aperture()) return "thinlens";
  if (sensor.model == FB_SENSOR_PHYSICAL)
    throw UsageError("--sensor-model physical needs an aperture: give --fstop (the shot has none)");
  return "perspective";
}

// A moving vertex may stray a twentieth of a pixel from its true path between motion steps: the
// pixel's footprint per metre of distance (perspective) or in metres (orthographic).
MotionTolerance motion_tolerance(const fb_camera_setup& setup) {
  constexpr double kPixels = 0.05;
  const ViewPlane v = view_plane(setup);
  const double footprint = kPixels / std::max(v.fx, v.fy);
  if (setup.projection == FB_PROJECTION_ORTHOGRAPHIC) return {footprint, 0};
  return {0, footprint};
}

// Adaptive subdivision's view of the shot: the camera and its view plane's pixels per metre.
SubdivView subdiv_view(const fb_camera_setup& setup, const SceneCamera& camera) {
  const ViewPlane v = view_plane(setup);
  return {camera.world_from_camera.inverse(), v.fx, v.fy,
          setup.projection == FB_PROJECTION_ORTHOGRAPHIC};
}

// A lens cannot focus closer than its focal length: the thin lens's image distance
// D_img = f D / (D - f) (1/f = 1/D + 1/D_img) is infinite at D = f and negative inside it
// (docs/camera-model.md). The error names where both values came from: a typed option is bad
// usage, else the scene's value is bad input.
void check_focus_beyond_focal_length(const SceneCamera& camera) {
  const PhysicalCamera& c = camera.physical;
  const double focal_m = c.focal_length_mm * 1e-3;
  if (c.projection != FB_PROJECTION_PERSPECTIVE || !c.has_aperture() ||
      c.focus_distance_m > focal_m)
    return;
  const ValueOrigin& focus = camera.origin(CameraValue::kFocusDistance);
  const ValueOrigin& focal = camera.origin(CameraValue::kFocalLength);
  const bool blame_focus = focus.typed() || !focal.typed();
  const std::string what =
      "focus distance " + number_text(c.focus_distance_m) + " m is not beyond the focal length " +
      number_text(c.focal_length_mm) + " mm (" +
      (blame_focus ? "focal length from " + focal.text() : "focus distance from " + focus.text()) +
      "): a lens cannot focus closer than its focal length (its image distance f D / (D - f) "
      "is infinite or negative); expected a focus distance over " +
      number_text(focal_m) + " m";
  (blame_focus ? focus : focal).fail(what);
}

// Splatting places each sample anywhere in its pixel and spreads it to the pixels within the
// filter's radius (docs/filters.md): a filter reaching less than half a pixel leaves pixels that
// no sample reaches, black in any scene.
void check_splat_reach(const FilterInstance& filter, const std::string& text,
                       Reconstruction reconstruction) {
  if (reconstruction != Reconstruction::kSplat) return;
  float radius[2];
  filter.radius(radius);
  if (radius[0] >= 0.5f && radius[1] >= 0.5f) return;
  throw UsageError("--reconstruction splat: the filter '" + text + "' reaches " +
                   number_text(std::min(radius[0], radius[1])) +
                   " px, expected at least 0.5 px (a splatted sample lies anywhere in its pixel, "
                   "and a narrower filter leaves pixels that no sample reaches); use "
                   "--reconstruction importance");
}

std::string describe_lens(const PhysicalCamera& camera, uint32_t needs) {
  if (!(needs & FB_CAMERA_NEEDS_LENS))
    return camera.projection == FB_PROJECTION_ORTHOGRAPHIC
               ? "no aperture: no lens samples"
               : "pinhole, no aperture: no lens samples";
  const std::string focus = std::isinf(camera.focus_distance_m)
                                ? "infinity"
                                : number_text(camera.focus_distance_m) + " m";
  return "f/" + number_text(camera.fstop) + " focused at " + focus + ": lens samples";
}

}  // namespace

std::pair<uint32_t, uint32_t> default_resolution(const SceneCamera& camera) {
  const double aspect = camera.intended_aspect.value_or(16.0 / 9.0);
  if (aspect >= 1.0)
    return {kDefaultLongSidePx,
            std::max<uint32_t>(1, uint32_t(std::lround(kDefaultLongSidePx / aspect)))};
  return {std::max<uint32_t>(1, uint32_t(std::lround(kDefaultLongSidePx * aspect))),
          kDefaultLongSidePx};
}

std::optional<std::string> shot_filter_text(const ShotSettings& shot) {
  if (!shot.filter) return std::nullopt;
  return plugin_text(filter_plugin_for(*shot.filter));
}

void CameraOverrides::apply(SceneCamera& camera) const {
  const auto typed = [&](CameraValue v, const std::optional<double>& x, const char* option) {
    if (!x) return;
    set_camera_value(camera.physical, v, *x);
    camera.origins[size_t(v)] = ValueOrigin::from_option(option);
  };
  using V = CameraValue;
  typed(V::kFocalLength, focal_length_mm, "--focal-length");
  typed(V::kFstop, fstop, "--fstop");
  typed(V::kFocusDistance, focus_distance_m, "--focus-distance");
  if (sensor_mm) {
    typed(V::kSensorWidth, sensor_mm->x, "--sensor");
    typed(V::kSensorHeight, sensor_mm->y, "--sensor");
  }
  if (sensor_fit) typed(V::kSensorFit, double(*sensor_fit), "--sensor-fit");
  if (shift) {
    typed(V::kShiftX, shift->x, "--shift");
    typed(V::kShiftY, shift->y, "--shift");
  }
}

RenderJob::RenderJob(const Scene& scene, const RenderOptions& options, const PluginLoader& loader)
    : scene_(scene), options_(options), plugins_(std::make_unique<Plugins>()) {
  // The frame's time on the scene's timeline, t = frame / fps (glTF's, as Blender writes it): each
  // from the command line, else the scene's extras, else frame 0 at kDefaultFps.
  frame_ = options.frame.value_or(scene.settings.frame.value_or(0.0));
  fps_ = options.fps.value_or(scene.settings.fps.value_or(kDefaultFps));
  const double frame_s = frame_ / fps_;
  const ShotSettings& shot = scene.settings;
  shutter_s_ = options.shutter_s.value_or(
      shot.shutter_open_s ? Vec2d{*shot.shutter_open_s, *shot.shutter_close_s} : Vec2d{0, 0});
  times_ = {frame_s, frame_s + shutter_s_.x, frame_s + shutter_s_.y};
  // The camera, its focus and the lights where they stand while the shutter is open.
  const double still_s = times_.still_s();
  camera_ = choose_camera(scene, options.camera, still_s);
  if (camera_.focus_track)
    camera_.physical.focus_distance_m = camera_.focus_track->at(still_s * fps_);
  options.camera_overrides.apply(camera_);
  check_focus_beyond_focal_length(camera_);
  if (options.width.has_value() != options.height.has_value())
    throw UsageError("--res: give both width and height");
  std::tie(width_, height_) = options.width   ? std::pair{*options.width, *options.height}
                              : shot.width_px ? std::pair{*shot.width_px, *shot.height_px}
                                              : default_resolution(camera_);
  spp_ = options.samples_per_pixel.value_or(kDefaultSamplesPerPixel);
  // A physical sensor integrates over the open shutter; an instantaneous one reports per second.
  const double open_s = shutter_s_.y - shutter_s_.x;
  sensor_ = SensorResponse{options.sensor_model, open_s > 0 ? open_s : 1.0, options.iso};

  Plugins& p = *plugins_;
  p.shutter_curve = shutter_curve(options.shutter_curve, shot);
  pixel_aspect_ = shot.pixel_aspect.value_or(1.0);
  p.integrator_text = options.integrator.value_or(kDefaultIntegrator);
  const fb_camera_setup setup =
      make_camera_setup(camera_.physical, width_, height_, pixel_aspect_, sensor_);
  p.camera = instantiate<CameraInstance>(
      loader, FB_KIND_CAMERA,
      options.camera_model.value_or(camera_model_for(camera_.physical, sensor_)), "--camera-model",
      setup);
  // --filter, else the shot's pixel filter with its exact values, else the default.
  if (!options.filter && shot.filter) {
    const TypedPlugin filter = filter_plugin_for(*shot.filter);
    p.filter_text = plugin_text(filter);
    p.filter = instantiate<FilterInstance>(loader, FB_KIND_FILTER, filter, shot.filter->origin);
  } else {
    p.filter_text = options.filter.value_or(kDefaultFilter);
    p.filter = instantiate<FilterInstance>(loader, FB_KIND_FILTER, p.filter_text, "--filter");
  }
  check_splat_reach(*p.filter, p.filter_text, options.reconstruction);
  p.integrator = instantiate<IntegratorInstance>(loader, FB_KIND_INTEGRATOR, p.integrator_text,
                                                 "--integrator");

  // Render space: world translated so the camera is at the origin; only this is narrowed to float.
  p.render_from_world = Transform::translate(-camera_.world_from_camera.translation());
  // Subdivision surfaces become triangles here, where the camera that adaptive refinement needs
  // is known; a scene without any never loads the subdivision module.
  const Scene* geometry_scene = &scene;
  if (options.subdiv == SubdivMode::kRender && !scene.subdivision_surfaces.empty()) {
    // Refining is itself the allocation to bound: its count is known from the cages.
    double triangles = double(scene.triangle_count()), texturing = texturing_bytes(scene);
    for (const SubdivisionSurface& surface : scene.subdivision_surfaces) {
      triangles += refined_triangles(surface);
      texturing += refined_texturing_bytes(surface);
    }
    check_memory_budget(triangles, texturing);
  }
  if (!scene.subdivision_surfaces.empty()) {
    p.refined = std::make_unique<Scene>(scene);
    SubdivReport report =
        refine_subdivision_surfaces(*p.refined, options.subdiv, subdiv_view(setup, camera_));
    for (const std::string& warning : report.warnings)
      std::cerr << "warning: " << warning << '\n';
    p.subdiv_summary = std::move(report.summary);
    geometry_scene = p.refined.get();
  }
  check_memory_budget(double(geometry_scene->triangle_count()), texturing_bytes(*geometry_scene));
  p.geometry = std::make_unique<RenderGeometry>(*geometry_scene, p.render_from_world, times_,
                                                motion_tolerance(setup));
  p.lights = std::make_unique<LightSampler>(*geometry_scene, p.render_from_world, *p.geometry,
                                            still_s, options.background);
  choose_time_samples(scene);
  for (const Material& m : scene.materials) {
    fb_material fm{};
    m.base_color.store(fm.base_color);
    m.emission.store(fm.emission);
    fm.double_sided = m.double_sided;
    p.materials.push_back(fm);
  }
  // The scene and its table as far as the integrator knows them (plugin_abi.h, "Growth").
  p.scene_api = host_scene_api();
  p.scene_api.struct_size = p.integrator->scene_api_size();
  p.scene.struct_size = p.integrator->scene_size();
  p.scene.api = &p.scene_api;
  p.scene.materials = p.materials.data();
  p.scene.material_count = uint32_t(p.materials.size());
  options.background.value_or(scene.background).store(p.scene.background);
  p.scene.scene_radius_m = length(p.geometry->bounds_centre()) + p.geometry->bounds_radius();
  Vec3f(normalize(camera_.world_from_camera.vector({0, 0, -1}))).store(p.scene.view_axis);

  camera_reason_ = describe_lens(camera_.physical, p.camera->needs());
}

RenderJob::~RenderJob() = default;

// The film, splat tiles and flattened geometry, against the limit, before any of them exists.
void RenderJob::check_memory_budget(double triangles, double texturing) const {
  const Plugins& p = *plugins_;
  float radius[2];
  p.filter->radius(radius);
  const MemoryEstimate estimate =
      estimate_memory(width_, height_, p.integrator->channels().size(), options_.reconstruction,
                      SplatTiles::reach(std::max(radius[0], radius[1])), triangles, texturing);
  if (options_.memory_limit_bytes)
    check_memory(estimate, *options_.memory_limit_bytes, "--memory-limit", scene_.file.string());
  else
    check_memory(estimate, default_memory_limit_bytes(),
                 "half of this machine's memory; --memory-limit sets another",
                 scene_.file.string());
}

// Time samples only when something moves while the shutter is open (docs/camera-model.md), and a
// camera path only when the camera moves; time_reason_ says which for the plan line.
void RenderJob::choose_time_samples(const Scene& scene) {
  Plugins& p = *plugins_;
  std::ostringstream out;
  out << "frame " << number_text(frame_) << " at " << number_text(fps_)
      << " fps (t = " << number_text(times_.frame_s) << " s), ";
  if (!times_.shutter_open()) {
    if (shutter_s_.x != 0)
      out << "zero-length shutter at t = " << number_text(times_.open_s) << " s";
    else
      out << "shutter closed";
    out << ": no time samples";
    time_reason_ = out.str();
    return;
  }
  const bool camera_moves = scene.moves(camera_.node_index, times_.open_s, times_.close_s);
  const size_t moving = p.geometry->moving_instance_count();
  const bool camera_needs_time = p.camera->needs() & FB_CAMERA_NEEDS_TIME;
  out << "shutter open " << number_text(shutter_s_.y - shutter_s_.x) << " s ("
      << p.shutter_curve.description() << ")";
  if (!camera_moves && moving == 0 && !camera_needs_time) {
    out << ", nothing moves in it: no time samples";
    time_reason_ = out.str();
    return;
  }
  p.time = {&p.shutter_curve, shutter_s_.x, shutter_s_.y};
  out << ": time samples for";
  if (moving > 0)
    out << " " << moving << " moving instance" << (moving > 1 ? "s" : "") << " (up to "
        << p.geometry->most_motion_steps() << " motion steps)";
  if (camera_moves) {
    p.camera_path =
        std::make_unique<CameraPath>(scene, camera_, p.render_from_world, times_.frame_s);
    out << (moving > 0 ? "," : "") << " the moving camera";
  }
  if (camera_needs_time) out << (moving > 0 || camera_moves ? "," : "") << " the camera plugin";
  time_reason_ = out.str();
}

namespace {

// "materials: 2 Blender 3.4.1 shader graphs (Cycles 3.4's closures), 1 glTF metallic-roughness":
// the models of the materials that geometry uses.
std::string material_models(const Scene& scene) {
  std::vector<bool> used(scene.materials.size(), false);
  for (const MeshInstance& i : scene.instances)
    used.at(scene.meshes[i.mesh].material) = true;
  for (const SubdivisionSurface& s : scene.subdivision_surfaces)
    for (const SubdivisionPart& part : s.parts)
      used.at(part.material) = true;
  const auto mark_solid = [&](const Solid& s, const auto& self) -> void {
    if (s.is_primitive()) used.at(s.material) = true;
    for (const Solid& child : s.children)
      self(child, self);
  };
  for (const Solid& s : scene.solids)
    mark_solid(s, mark_solid);
  std::map<std::string, size_t> counts;
  for (size_t m = 0; m < used.size(); ++m) {
    if (!used[m]) continue;
    const std::optional<ShaderGraph>& graph = scene.materials[m].shader_graph;
    ++counts[!graph ? "glTF metallic-roughness"
                    : "Blender " +
                          (graph->blender_version.empty() ? std::string()
                                                          : graph->blender_version + " ") +
                          "shader graph" + " (Cycles 3.4's closures)"];
  }
  std::string out = "materials:";
  for (const auto& [model, n] : counts)
    out += (out.back() == ':' ? " " : ", ") + std::to_string(n) + " " + model;
  return counts.empty() ? "no materials" : out;
}

}  // namespace

RenderChoices RenderJob::choices() const {
  const Plugins& p = *plugins_;
  return {camera_.name,
          camera_.source,
          p.camera->name(),
          camera_reason_,
          p.filter_text,
          reconstruction_name(options_.reconstruction),
          p.integrator_text,
          sampler_name(options_.sampler),
          time_reason_,
          p.subdiv_summary,
          material_models(scene_),
          p.geometry->triangle_count(),
          p.lights->lamp_count(),
          p.lights->emissive_triangle_count()};
}

std::string RenderJob::plan() const {
  const RenderChoices c = choices();
  std::ostringstream out;
  out << "filmback: camera '" << c.camera << "' (" << c.camera_source << ") through "
      << c.camera_model << " (" << c.lens << "), " << width_ << "x" << height_ << ", " << spp_
      << " spp (" << c.sampler << "), filter " << c.filter << " (" << c.reconstruction
      << "), integrator " << c.integrator << "; " << c.time << "; " << c.triangles << " triangles, "
      << c.lights << " lights, " << c.emissive_triangles << " emissive triangles";
  if (!c.subdivision.empty()) out << "; " << c.subdivision;
  out << "; " << c.materials;
  return out.str();
}

Film RenderJob::make_film() const {
  return Film(width_, height_, plugins_->integrator->channels());
}

RenderResult RenderJob::run() const {
  Film film = make_film();
  return run(film);
}

RenderResult RenderJob::run(Film& film, const RenderControl& control) const {
  const Plugins& p = *plugins_;
  RenderInputs inputs{*p.camera,
                      *p.filter,
                      *p.integrator,
                      *p.geometry,
                      *p.lights,
                      p.scene,
                      camera_.world_from_camera.without_scale_and_translation(),
                      spp_,
                      options_.sampler,
                      options_.seed,
                      options_.reconstruction};
  inputs.time = p.time;
  inputs.camera_path = p.camera_path.get();
  std::optional<Progress> progress;
  if (options_.show_progress)
    progress.emplace(sample_count(inputs, width_, height_), std::cerr, stderr_is_terminal());
  RenderResult result;
  result.stats = render_image(inputs, film, control, progress ? &*progress : nullptr);
  progress.reset();
  result.image = film.resolve();
  Image& image = result.image;
  // Cycles' Film > Exposure: a gain on the rendered radiance, colour channels only.
  if (const double gain = scene_.settings.film_exposure; gain != 1.0)
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
      for (size_t c = 0; c < 3; ++c)
        image.pixels[i * image.channels.size() + c] *= float(gain);
  const uint32_t* counts = film.sample_counts();
  const auto [fewest, most] = std::minmax_element(counts, counts + film.pixel_count());
  result.fewest_samples = *fewest, result.most_samples = *most;
  if (result.stats.interrupted) {  // say per pixel how far it got
    const size_t n = image.channels.size();
    std::vector<float> pixels(film.pixel_count() * (n + 1));
    for (size_t i = 0; i < film.pixel_count(); ++i) {
      std::copy_n(&image.pixels[i * n], n, &pixels[i * (n + 1)]);
      pixels[i * (n + 1) + n] = float(counts[i]);
    }
    image.pixels = std::move(pixels);
    image.channels.push_back("samples");
  }
  return result;
}

ImageMetadata RenderJob::metadata(const RenderResult& result) const {
  const RenderStats& stats = result.stats;
  const fb_camera_setup setup =
      make_camera_setup(camera_.physical, width_, height_, pixel_aspect_, sensor_);
  const Transform camera_from_world = camera_.world_from_camera.inverse();
  ImageMetadata m;
  // OpenEXR's camera space looks down +Z (ImfStandardAttributes.h, worldToCamera); ours, glTF's,
  // looks down -Z: flip z. worldToNDC needs no flip.
  const Transform exr_camera_from_world = Transform::scale({1, 1, -1}) * camera_from_world;
  m.matrices = {{"worldToCamera", to_float_matrix(exr_camera_from_world)},
                {"worldToNDC", to_float_matrix(ndc_from_camera(setup) * camera_from_world)}};
  if (setup.projection == FB_PROJECTION_PERSPECTIVE)
    m.floats.push_back({"filmback/focal_length_mm", float(setup.focal_length_mm)});
  m.floats.insert(m.floats.end(), {{"filmback/sensor_width_mm", float(setup.sensor_width_mm)},
                                   {"filmback/sensor_height_mm", float(setup.sensor_height_mm)},
                                   {"filmback/shift_x", float(setup.shift_x)},
                                   {"filmback/shift_y", float(setup.shift_y)},
                                   {"filmback/render_seconds", float(stats.seconds)}});
  // OpenEXR's standard lens and exposure attributes (ImfStandardAttributes.h: focus in scene units,
  // aperture as the f-number, expTime in seconds, isoSpeed), as OIIO names them.
  if (camera_.physical.has_aperture()) {
    m.floats.push_back({"FNumber", float(setup.fstop)});
    if (std::isfinite(setup.focus_distance_m))
      m.floats.push_back({"focus", float(setup.focus_distance_m)});
  }
  if (setup.sensor_model == FB_SENSOR_PHYSICAL)
    m.floats.insert(m.floats.end(), {{"ExposureTime", float(setup.exposure_time_s)},
                                     {"isoSpeed", float(setup.iso)}});
  m.ints = {
      {"filmback/samples_per_pixel", int(spp_)},
      {"filmback/dropped_samples", int(std::min<uint64_t>(stats.dropped_samples, INT32_MAX))}};
  if (stats.interrupted)
    m.ints.insert(m.ints.end(), {{"filmback/interrupted", 1},
                                 {"filmback/fewest_samples", int(result.fewest_samples)},
                                 {"filmback/most_samples", int(result.most_samples)}});
  m.strings = {{"Software", "filmback"},
               {"filmback/scene", scene_.file.filename().string()},
               {"filmback/camera", camera_.name},
               {"filmback/sensor_fit", sensor_fit_name(setup.sensor_fit)},
               {"filmback/camera_model", plugins_->camera->name()},
               {"filmback/filter", plugins_->filter_text},
               {"filmback/reconstruction", reconstruction_name(options_.reconstruction)},
               {"filmback/sampler", sampler_name(options_.sampler)},
               {"filmback/integrator", plugins_->integrator_text}};
  return m;
}

}  // namespace fb
