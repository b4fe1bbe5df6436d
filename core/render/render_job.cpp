#include "core/render/render_job.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

#include <filmback/camera_projection.h>
#include <filmback/render_passes.h>

#include "core/accel/render_geometry.h"
#include "core/film/splat_tiles.h"
#include "core/plugin/instances.h"
#include "core/render/blender_layers.h"
#include "core/render/cryptomatte_layers.h"
#include "core/render/light_sampler.h"
#include "core/render/memory_estimate.h"
#include "core/render/motion.h"
#include "core/render/plugin_choice_loader.h"
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
  std::unique_ptr<RenderGeometry> geometry;
  std::unique_ptr<LightSampler> lights;
  std::optional<RenderMedia> media;  // the scene's global media, if it has any
  TimeSampling time;
  std::unique_ptr<CameraPath> camera_path;
  std::unique_ptr<MotionVectors> motion_vectors;  // only when --passes asks for Vector
  std::unique_ptr<Scene> refined;  // the scene with its subdivision surfaces made triangles
  std::string subdiv_summary;
  std::vector<fb_material> materials;
  std::vector<fb_pov_finish> pov_finishes;  // per material, for a POV-Ray scene
  fb_povray_scene povray{};
  std::vector<fb_medium> interior_media;  // per material, when one holds a medium
  fb_scene_api scene_api{};               // host_scene_api(), as long as the integrator knows it
  fb_scene scene{};
};

namespace {

ImageMetadata::Matrix to_float_matrix(const Transform& t) {
  ImageMetadata::Matrix m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      m[r * 4 + c] = float(t(r, c));
  return m;
}

fb_medium to_abi(const InteriorMedium& m) {
  fb_medium out{};
  out.present = 1;
  m.absorption.store(out.absorption);
  m.scattering.store(out.scattering);
  m.emission.store(out.emission);
  m.povray_extinction.store(out.povray_extinction);
  out.povray_points = m.povray_points;
  return out;
}

fb_pov_finish to_abi(const PovFinish& f) {
  fb_pov_finish out{};
  out.present = 1;
  f.pigment.store(out.pigment);
  out.pigment_scale = f.pigment_scale;
  out.filter = f.filter, out.transmit = f.transmit, out.coverage = f.coverage;
  f.ambient.store(out.ambient);
  f.emission.store(out.emission);
  out.diffuse = f.diffuse, out.brilliance = f.brilliance;
  out.phong = f.phong, out.phong_size = f.phong_size;
  out.specular = f.specular, out.roughness = f.roughness;
  out.metallic = f.metallic;
  f.reflection_min.store(out.reflection_min);
  f.reflection_max.store(out.reflection_max);
  out.reflection_falloff = f.reflection_falloff;
  out.reflection_exponent = f.reflection_exponent;
  out.reflection_fresnel = f.reflection_fresnel;
  out.reflection_metallic = f.reflection_metallic;
  out.ior = f.ior;
  return out;
}

// OpenEXR's camera space looks down +Z (ImfStandardAttributes.h, worldToCamera), as Cycles' does;
// ours, glTF's, looks down -Z: flip z. worldToNDC needs no flip.
Transform exr_camera_from_world(const SceneCamera& camera) {
  return Transform::scale({1, 1, -1}) * camera.world_from_camera.inverse();
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

// ", adaptive: threshold 0.01, at least 64 samples" (the threshold as typed, Cycles' units).
std::string adaptive_text(const ShotPlan& plan) {
  if (!plan.adaptive) return "";
  return ", adaptive: threshold " + number_text(plan.adaptive_request.threshold) + ", at least " +
         std::to_string(plan.adaptive->min_samples) + " samples";
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

RenderJob::RenderJob(const Scene& scene, const RenderOptions& options, const PluginLoader& loader)
    : scene_(scene),
      options_(options),
      plan_(plan_shot(scene, options)),
      plugins_(std::make_unique<Plugins>()) {
  load_plugins(loader);
  build_geometry();
  choose_time_samples();
  make_scene_table();
  camera_reason_ = describe_lens(plan_.camera.physical, plugins_->camera->needs());
}

void RenderJob::load_plugins(const PluginLoader& loader) {
  Plugins& p = *plugins_;
  p.camera = load_camera(loader, plan_);
  p.filter = load_filter(loader, plan_.filter);
  check_splat_reach(*p.filter, plan_.filter.text(), options_.reconstruction);
  p.integrator = load_integrator(loader, plan_.integrator);
}

// Render space: world translated so the camera is at the origin; only this is narrowed to float.
// Subdivision surfaces become triangles here, where the camera that adaptive refinement needs is
// known; a scene without any never loads the subdivision module.
void RenderJob::build_geometry() {
  Plugins& p = *plugins_;
  const SceneCamera& camera = plan_.camera;
  const fb_camera_setup setup = plan_.camera_setup();
  p.render_from_world = Transform::translate(-camera.world_from_camera.translation());
  const Scene* geometry_scene = &scene_;
  if (options_.subdiv == SubdivMode::kRender && !scene_.subdivision_surfaces.empty()) {
    // Refining is itself the allocation to bound: its count is known from the cages.
    GeometryCounts counts = geometry_counts(scene_);
    for (const SubdivisionSurface& surface : scene_.subdivision_surfaces)
      counts += {refined_triangles(surface), 0, refined_texturing_bytes(surface)};
    check_memory_budget(counts);
  }
  if (!scene_.subdivision_surfaces.empty()) {
    p.refined = std::make_unique<Scene>(scene_);
    SubdivReport report =
        refine_subdivision_surfaces(*p.refined, options_.subdiv, subdiv_view(setup, camera));
    for (const std::string& warning : report.warnings)
      std::cerr << "warning: " << warning << '\n';
    p.subdiv_summary = std::move(report.summary);
    geometry_scene = p.refined.get();
  }
  check_memory_budget(geometry_counts(*geometry_scene));
  p.geometry = std::make_unique<RenderGeometry>(*geometry_scene, p.render_from_world, plan_.times,
                                                motion_tolerance(setup));
  p.lights = std::make_unique<LightSampler>(*geometry_scene, p.render_from_world, *p.geometry,
                                            plan_.times.still_s(), options_.background,
                                            options_.light_selection);
  if (std::find(options_.passes.begin(), options_.passes.end(), kVectorPass) !=
      options_.passes.end())
    p.motion_vectors = std::make_unique<MotionVectors>(*geometry_scene, plan_, p.render_from_world);
  if (!scene_.media.empty()) p.media.emplace(scene_.media, p.render_from_world.inverse());
}

// The scene and its table as far as the integrator knows them (plugin_abi.h, "Growth").
void RenderJob::make_scene_table() {
  Plugins& p = *plugins_;
  for (const Material& m : scene_.materials) {
    fb_material fm{};
    m.base_color.store(fm.base_color);
    m.emission.store(fm.emission);
    fm.double_sided = m.double_sided;
    p.materials.push_back(fm);
  }
  p.scene_api = host_scene_api();
  p.scene_api.struct_size = p.integrator->scene_api_size();
  p.scene.struct_size = p.integrator->scene_size();
  p.scene.api = &p.scene_api;
  p.scene.materials = p.materials.data();
  p.scene.material_count = uint32_t(p.materials.size());
  options_.background.value_or(scene_.background).store(p.scene.background);
  p.scene.scene_radius_m = length(p.geometry->bounds_centre()) + p.geometry->bounds_radius();
  Vec3f(normalize(plan_.camera.world_from_camera.vector({0, 0, -1}))).store(p.scene.view_axis);
  p.scene.lamp_count = uint32_t(p.lights->lamp_count());
  if (scene_.pov_tracing) {
    for (const Material& m : scene_.materials)
      p.pov_finishes.push_back(m.pov_finish ? to_abi(*m.pov_finish) : fb_pov_finish{});
    const PovTracing& tracing = *scene_.pov_tracing;
    p.povray = {sizeof(fb_povray_scene),
                tracing.max_trace_level,
                float(tracing.adc_bailout),
                uint32_t(p.pov_finishes.size()),
                p.pov_finishes.data(),
                float(tracing.colour_gamma),
                {tracing.ambient_light.x, tracing.ambient_light.y, tracing.ambient_light.z}};
    p.scene.povray = &p.povray;
  }
  if (std::any_of(scene_.materials.begin(), scene_.materials.end(),
                  [](const Material& m) { return m.medium.has_value(); })) {
    for (const Material& m : scene_.materials)
      p.interior_media.push_back(m.medium ? to_abi(*m.medium) : fb_medium{});
    p.scene.media = p.interior_media.data();
  }
}

RenderJob::~RenderJob() = default;

// The film, splat tiles, flattened geometry and pass films, against the limit, before any of them
// exists.
void RenderJob::check_memory_budget(const GeometryCounts& geometry) const {
  const Plugins& p = *plugins_;
  float radius[2];
  p.filter->radius(radius);
  const MemoryEstimate estimate = estimate_memory(
      plan_.width_px, plan_.height_px, p.integrator->channels().size(), options_.reconstruction,
      SplatTiles::reach(std::max(radius[0], radius[1])), geometry,
      pass_film_counts(options_.passes,
                       options_.cryptomatte_levels.value_or(kDefaultCryptomatteLevels)));
  if (options_.memory_limit_bytes)
    check_memory(estimate, *options_.memory_limit_bytes, "--memory-limit", scene_.file.string());
  else
    check_memory(estimate, default_memory_limit_bytes(),
                 "half of this machine's memory; --memory-limit sets another",
                 scene_.file.string());
}

// Time samples only when something moves while the shutter is open (docs/camera-model.md), and a
// camera path only when the camera moves; time_reason_ says which for the plan line.
void RenderJob::choose_time_samples() {
  const ShotTimes& times = plan_.times;
  const Vec2d& shutter_s = plan_.shutter_s;
  Plugins& p = *plugins_;
  std::ostringstream out;
  out << "frame " << number_text(plan_.frame) << " at " << number_text(plan_.fps)
      << " fps (t = " << number_text(times.frame_s) << " s), ";
  if (!times.shutter_open()) {
    if (shutter_s.x != 0)
      out << "zero-length shutter at t = " << number_text(times.open_s) << " s";
    else
      out << "shutter closed";
    out << ": no time samples";
    time_reason_ = out.str();
    return;
  }
  const bool camera_moves = scene_.moves(plan_.camera.node_index, times.open_s, times.close_s);
  const size_t moving = p.geometry->moving_instance_count();
  const bool camera_needs_time = p.camera->needs() & FB_CAMERA_NEEDS_TIME;
  const bool zooms = plan_.zoom.has_value();
  out << "shutter open " << number_text(shutter_s.y - shutter_s.x) << " s ("
      << plan_.shutter_curve.description();
  if (plan_.rolling_shutter) out << ", " << plan_.rolling_shutter->description();
  out << ")";
  if (!camera_moves && moving == 0 && !camera_needs_time && !zooms) {
    out << ", nothing moves in it: no time samples";
    time_reason_ = out.str();
    return;
  }
  p.time = {&plan_.shutter_curve, shutter_s.x, shutter_s.y, plan_.rolling_shutter, plan_.height_px};
  out << ": time samples for";
  if (moving > 0)
    out << " " << moving << " moving instance" << (moving > 1 ? "s" : "") << " (up to "
        << p.geometry->most_motion_steps() << " motion steps)";
  if (camera_moves) {
    p.camera_path =
        std::make_unique<CameraPath>(scene_, plan_.camera, p.render_from_world, times.frame_s);
    out << (moving > 0 ? "," : "") << " the moving camera";
  }
  if (camera_needs_time) out << (moving > 0 || camera_moves ? "," : "") << " the camera plugin";
  if (zooms)
    out << (moving > 0 || camera_moves || camera_needs_time ? "," : "") << " the zoom (x"
        << number_text(plan_.zoom->k_open) << " to x" << number_text(plan_.zoom->k_close)
        << " of the view at the shutter's centre)";
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
  return {plan_.camera.name,
          plan_.camera.source,
          p.camera->name(),
          camera_reason_,
          plan_.filter.text(),
          reconstruction_name(options_.reconstruction),
          plan_.integrator.text(),
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
      << c.camera_model << " (" << c.lens << "), " << plan_.width_px << "x" << plan_.height_px
      << ", " << plan_.samples_per_pixel << " spp (" << c.sampler << adaptive_text(plan_)
      << "), filter " << c.filter << " (" << c.reconstruction << "), integrator " << c.integrator
      << "; " << c.time << "; " << c.triangles << " triangles, " << c.lights << " lights, "
      << c.emissive_triangles << " emissive triangles";
  if (!c.subdivision.empty()) out << "; " << c.subdivision;
  out << "; " << c.materials;
  return out.str();
}

Film RenderJob::make_film() const {
  return Film(plan_.width_px, plan_.height_px, plugins_->integrator->channels());
}

SamplingState RenderJob::make_sampling_state() const {
  SamplingState state;
  prepare_sampling_state(inputs(std::nullopt), plan_.width_px, plan_.height_px, state);
  return state;
}

RenderResult RenderJob::run(Film& film) const {
  SamplingState state;
  return run(film, state);
}

RenderResult RenderJob::run() const {
  Film film = make_film();
  return run(film);
}

PixelRect RenderJob::part_tiles(const PixelRect& crop) const {
  return whole_tiles_around(
      part_region(crop, plan_.adaptive, plan_.samples_per_pixel, plan_.width_px, plan_.height_px),
      plan_.width_px, plan_.height_px);
}

void apply_film_exposure(Image& image, double gain) {
  if (gain == 1.0) return;
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
    for (size_t c = 0; c < 3; ++c)
      image.pixels[i * image.channels.size() + c] *= float(gain);
}

RenderInputs RenderJob::inputs(const std::optional<PixelRect>& crop) const {
  const Plugins& p = *plugins_;
  RenderInputs inputs{*p.camera,
                      *p.filter,
                      *p.integrator,
                      *p.geometry,
                      *p.lights,
                      p.scene,
                      plan_.camera.world_from_camera.without_scale_and_translation(),
                      plan_.samples_per_pixel,
                      options_.sampler,
                      options_.seed,
                      options_.reconstruction};
  inputs.time = p.time;
  inputs.adaptive = plan_.adaptive;
  inputs.exposure = scene_.settings.film_exposure;
  inputs.camera_path = p.camera_path.get();
  if (p.time.curve && plan_.zoom) inputs.zoom = &*plan_.zoom;
  inputs.texture_footprint = options_.texture_footprint && !scene_.images.empty();
  inputs.media = p.media ? &*p.media : nullptr;
  inputs.crop = crop;
  return inputs;
}

Image RenderJob::resolve(const Film& film) const {
  Image image = film.resolve();
  apply_film_exposure(image, scene_.settings.film_exposure);
  if (!options_.passes.empty()) {
    name_beauty_as_combined(image);
    denoising_normal_to_camera_space(image, exr_camera_from_world(plan_.camera));
    rename_view_layer(image, options_.view_layer);
  }
  return image;
}

Image RenderJob::image_so_far(const Film& film, const SamplingState& state) const {
  if (state.splat_tiles.empty()) return resolve(film);
  // Film keeps its arrays to itself (zeroed pages, not copyable): a copy through its raw state.
  Film with_splats(film.width(), film.height(), film.channels());
  std::copy_n(film.sums(), film.pixel_count() * film.channels().size(), with_splats.sums());
  std::copy_n(film.weights(), film.pixel_count(), with_splats.weights());
  SplatTiles::add_splat_tiles(state.splat_tiles, with_splats);
  return resolve(with_splats);
}

RenderResult RenderJob::run(Film& film, SamplingState& state, const RenderControl& control,
                            const std::optional<PixelRect>& crop) const {
  RenderInputs inputs = this->inputs(crop);
  std::optional<Progress> progress;
  if (options_.show_progress)
    progress.emplace(sample_count(inputs, plan_.width_px, plan_.height_px), std::cerr,
                     stderr_is_terminal(), options_.progress_every);
  RenderResult result;
  const Scene& geometry_scene = plugins_->refined ? *plugins_->refined : scene_;
  std::optional<CryptomatteFilm> cryptomatte;
  if (auto layers = cryptomatte_layers(geometry_scene, options_.passes); !layers.empty()) {
    cryptomatte.emplace(film.width(), film.height(), std::move(layers),
                        options_.cryptomatte_levels.value_or(kDefaultCryptomatteLevels));
    inputs.cryptomatte = &*cryptomatte;
  }
  std::optional<MotionVectorFilm> motion_vector_film;
  if (plugins_->motion_vectors) {
    motion_vector_film.emplace(film.width(), film.height());
    inputs.motion_vectors = plugins_->motion_vectors.get();
    inputs.motion_vector_film = &*motion_vector_film;
  }
  result.stats = render_image(inputs, film, state, control, progress ? &*progress : nullptr);
  progress.reset();
  if (!crop && !result.stats.interrupted) state.splat_tiles.clear();
  result.image = resolve(film);
  Image& image = result.image;
  if (cryptomatte) {
    cryptomatte->append_layers(image, options_.view_layer);
    result.cryptomatte_metadata = cryptomatte->metadata(options_.view_layer);
  }
  if (motion_vector_film) motion_vector_film->append_pass(image, options_.view_layer);
  const uint32_t* counts = film.sample_counts();
  // Over the pixels rendered: a part's crop, or the whole frame.
  const PixelRect rendered = crop.value_or(whole_frame(film.width(), film.height()));
  result.fewest_samples = UINT32_MAX, result.most_samples = 0;
  for (uint32_t y = rendered.y0; y < rendered.y1; ++y)
    for (uint32_t x = rendered.x0; x < rendered.x1; ++x) {
      result.fewest_samples = std::min(result.fewest_samples, film.sample_count(x, y));
      result.most_samples = std::max(result.most_samples, film.sample_count(x, y));
    }
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
  const fb_camera_setup setup = plan_.camera_setup();
  const Transform camera_from_world = plan_.camera.world_from_camera.inverse();
  ImageMetadata m;
  m.matrices = {{"worldToCamera", to_float_matrix(exr_camera_from_world(plan_.camera))},
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
  if (plan_.camera.physical.has_aperture()) {
    m.floats.push_back({"FNumber", float(setup.fstop)});
    if (std::isfinite(setup.focus_distance_m))
      m.floats.push_back({"focus", float(setup.focus_distance_m)});
  }
  if (setup.sensor_model == FB_SENSOR_PHYSICAL)
    m.floats.insert(m.floats.end(), {{"ExposureTime", float(setup.exposure_time_s)},
                                     {"isoSpeed", float(setup.iso)}});
  m.ints = {
      {"filmback/samples_per_pixel", int(plan_.samples_per_pixel)},
      {"filmback/dropped_samples", int(std::min<uint64_t>(stats.dropped_samples, INT32_MAX))}};
  if (stats.interrupted)
    m.ints.insert(m.ints.end(), {{"filmback/interrupted", 1},
                                 {"filmback/fewest_samples", int(result.fewest_samples)},
                                 {"filmback/most_samples", int(result.most_samples)}});
  m.strings = {{"Software", "filmback"},
               {"filmback/scene", scene_.file.filename().string()},
               {"filmback/camera", plan_.camera.name},
               {"filmback/sensor_fit", sensor_fit_name(setup.sensor_fit)},
               {"filmback/camera_model", plugins_->camera->name()},
               {"filmback/filter", plan_.filter.text()},
               {"filmback/reconstruction", reconstruction_name(options_.reconstruction)},
               {"filmback/sampler", sampler_name(options_.sampler)},
               {"filmback/integrator", plan_.integrator.text()}};
  // Blender's own multi-layer EXRs carry this marker (a Cycles render written with `blender -b`);
  // Blender's reader takes a file with it for one with layers and passes.
  if (!options_.passes.empty())
    m.strings.push_back({"BlenderMultiChannel", "Blender V2.55.1 and newer"});
  m.strings.insert(m.strings.end(), result.cryptomatte_metadata.begin(),
                   result.cryptomatte_metadata.end());
  return m;
}

}  // namespace fb
