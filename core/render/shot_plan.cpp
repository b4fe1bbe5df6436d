#include "core/render/shot_plan.h"

#include <algorithm>
#include <cmath>

#include <filmback/camera_projection.h>

#include "core/film/cryptomatte.h"
#include "core/plugin/params.h"
#include "core/render/motion_vectors.h"
#include "core/scene/default_camera.h"
#include "core/util/error.h"

namespace fb {
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

// The rolling shutter: --rolling-shutter, else the shot's; none while the shutter is closed, as
// Cycles rolls it only with motion blur on (its shuttertime is -1 then: kernel/camera/camera.h).
std::optional<RollingShutter> rolling_shutter(
    const std::optional<std::optional<RollingShutter>>& typed, const ShotSettings& shot,
    const ShotTimes& times) {
  std::optional<RollingShutter> rolling;
  if (typed)
    rolling = *typed;
  else if (shot.rolling_shutter_duration)
    rolling = RollingShutter{*shot.rolling_shutter_duration};
  if (times.shutter_open()) return rolling;
  if (typed && *typed)
    throw UsageError(
        "--rolling-shutter: the shutter is closed; give --shutter OPEN,CLOSE (a rolling shutter "
        "reads its rows while it is open)");
  return std::nullopt;
}

// A plugin named in an option's text ("NAME[:k=v,...]"); a malformed text is that option's error.
PluginChoice typed_choice(const std::string& text, const char* option) {
  PluginSpec spec = parse_plugin_spec(text, option);
  return {std::move(spec.name), std::move(spec.settings), {}, ValueOrigin::from_option(option)};
}

// --- The one table from a shot to plugins (tests/layers/check_layers.py allows plugin names
// --- here and nowhere else in core).

constexpr const char* kDefaultFilter = "gaussian";
constexpr const char* kDefaultIntegrator = "path";

// Cycles' pixel filters as filter plugins (docs/filters.md, "Against Blender"): Blackman-Harris of
// width w spans +-w; the Gaussian of width w is exp(-8x^2/w^2) (sigma = w/4) cut at +-1.5w; the box
// of width w spans +-w/2.
PluginChoice filter_for(const PixelFilterSetting& filter) {
  const double w = filter.width_px;
  const auto number = [&](const char* key, double x) { return NamedNumber{key, x, filter.origin}; };
  switch (filter.type) {
    case PixelFilterSetting::Type::kGaussian:
      return {"gaussian", {}, {number("radius", 1.5 * w), number("sigma", w / 4)}, filter.origin};
    case PixelFilterSetting::Type::kBox:
      return {"box", {}, {number("radius", w / 2)}, filter.origin};
    case PixelFilterSetting::Type::kBlackmanHarris:
      break;
  }
  return {"blackman_harris", {}, {number("width", w)}, filter.origin};
}

// --filter, else the shot's pixel filter with its exact values, else the default.
PluginChoice choose_filter(const std::optional<std::string>& typed, const ShotSettings& shot) {
  if (typed) return typed_choice(*typed, "--filter");
  if (shot.filter) return filter_for(*shot.filter);
  return {kDefaultFilter, {}, {}, ValueOrigin::by_default("the shot names no pixel filter")};
}

// The lens values as parameters of the camera plugin (thinlens's schema: docs/camera-model.md).
// The f-number travels as itself: the plugin alone turns f/N into an aperture radius f / 2N.
std::vector<NamedNumber> lens_numbers(const SceneCamera& camera) {
  const PhysicalCamera& c = camera.physical;
  std::vector<NamedNumber> numbers;
  const auto add = [&](const char* key, double x, CameraValue v) {
    numbers.push_back({key, x, camera.origin(v)});
  };
  if (c.has_aperture()) add("fstop", c.fstop, CameraValue::kFstop);
  add("focus_distance_m", c.focus_distance_m, CameraValue::kFocusDistance);
  add("aperture_blades", c.aperture_blades, CameraValue::kApertureBlades);
  add("aperture_rotation_rad", c.aperture_rotation_rad, CameraValue::kApertureRotation);
  add("aperture_ratio", c.aperture_ratio, CameraValue::kApertureRatio);
  numbers.insert(numbers.end(), camera.lens_distortion.begin(), camera.lens_distortion.end());
  return numbers;
}

// The shot's values for a camera plugin: its lens, then its own projection's values, if any.
std::vector<NamedNumber> camera_numbers(const SceneCamera& camera) {
  std::vector<NamedNumber> numbers = lens_numbers(camera);
  if (camera.model)
    numbers.insert(numbers.end(), camera.model->numbers.begin(), camera.model->numbers.end());
  return numbers;
}

// Projections a scene names (CameraModel::kind), each rendered by the camera plugin of its name
// (docs/camera-model.md): Cycles 3.4's panorama types and Blender's later ones, and POV-Ray's.
constexpr std::string_view kModelPlugins[] = {
    "equirectangular",
    "fisheye_equidistant",
    "fisheye_equisolid",
    "mirrorball",
    "fisheye_polynomial",
    "central_cylindrical",
    "equiangular_cubemap_face",
    // POV-Ray 3.7's camera types (importers/pov/pov_camera.cpp)
    "pov_fisheye",
    "pov_ultra_wide_angle",
    "pov_omnimax",
    "pov_panoramic",
    "pov_cylinder",
    "pov_spherical",
};

PluginChoice model_plugin(const CameraModel& model, std::vector<NamedNumber> numbers) {
  std::string kinds;
  for (std::string_view plugin : kModelPlugins) {
    if (plugin == model.kind) return {model.kind, {}, std::move(numbers), model.origin};
    kinds.append(kinds.empty() ? "" : ", ").append(plugin);
  }
  model.origin.fail("no camera plugin renders the projection '" + model.kind +
                    "'; expected one of " + kinds);
}

// --camera-model (given the shot's values where it declares them), else only what the shot
// needs: its own projection's plugin, else a pinhole unless it has an aperture
// (docs/camera-model.md).
PluginChoice choose_camera_model(const std::optional<std::string>& typed, const SceneCamera& camera,
                                 const SensorResponse& sensor) {
  const PhysicalCamera& c = camera.physical;
  if (typed) {
    PluginChoice choice = typed_choice(*typed, "--camera-model");
    choice.numbers = camera_numbers(camera);
    return choice;
  }
  if (c.projection == FB_PROJECTION_ORTHOGRAPHIC) {
    if (sensor.model == FB_SENSOR_PHYSICAL)
      throw UsageError(
          "--sensor-model physical: an orthographic camera has no aperture to expose through");
    return {"orthographic", {}, camera.lens_distortion, camera.origin(CameraValue::kOrthoScale)};
  }
  if (sensor.model == FB_SENSOR_PHYSICAL && !c.has_aperture())
    throw UsageError("--sensor-model physical needs an aperture: give --fstop (the shot has none)");
  if (camera.model) return model_plugin(*camera.model, camera_numbers(camera));
  if (c.has_aperture())
    return {"thinlens", {}, lens_numbers(camera), camera.origin(CameraValue::kFstop)};
  return {"perspective", {}, camera.lens_distortion, camera.origin(CameraValue::kFstop)};
}

}  // namespace

std::optional<uint32_t> blender_projection(const PluginChoice& camera_model) {
  if (camera_model.name == "orthographic") return FB_PROJECTION_ORTHOGRAPHIC;
  if (camera_model.name == "perspective" || camera_model.name == "thinlens")
    return FB_PROJECTION_PERSPECTIVE;
  return std::nullopt;
}

namespace {

// --passes reaches the integrator as its parameter `passes` (docs/plugins.md, "Render passes"),
// but for the Cryptomatte passes and Vector, which the host writes (core/film/cryptomatte.h,
// core/film/motion_vector_film.h).
PluginChoice choose_integrator(const std::optional<std::string>& typed,
                               const std::vector<std::string>& passes) {
  PluginChoice choice =
      typed ? typed_choice(*typed, "--integrator")
            : PluginChoice{
                  kDefaultIntegrator, {}, {}, ValueOrigin::by_default("--integrator not given")};
  if (!passes.empty()) {
    std::string list;
    for (const std::string& pass : passes)
      if (!find_cryptomatte_pass(pass) && pass != kVectorPass)
        list += (list.empty() ? "" : ",") + pass;
    if (!list.empty()) choice.typed.emplace_back("passes", list);
  }
  return choice;
}

// --- end of the table

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

// The frame's time on the scene's timeline, t = frame / fps (glTF's, as Blender writes it), and the
// shutter around it: each from the command line, else the scene's settings, else frame 0 at
// kDefaultFps with a closed shutter.
void plan_times(const ShotSettings& shot, const RenderOptions& options, ShotPlan& plan) {
  plan.frame = options.frame.value_or(shot.frame.value_or(0.0));
  plan.fps = options.fps.value_or(shot.fps.value_or(kDefaultFps));
  const double frame_s = plan.frame / plan.fps;
  plan.shutter_s = options.shutter_s.value_or(
      shot.shutter_open_s ? Vec2d{*shot.shutter_open_s, *shot.shutter_close_s} : Vec2d{0, 0});
  plan.times = {frame_s, frame_s + plan.shutter_s.x, frame_s + plan.shutter_s.y};
  plan.shutter_curve = shutter_curve(options.shutter_curve, shot);
  plan.rolling_shutter = rolling_shutter(options.rolling_shutter, shot, plan.times);
}

// The shutter's centre as a frame number: where Cycles syncs the field of view when the shutter
// is open (blender/camera.cpp, sync_camera_motion at motion time 0), else the frame.
double centre_frame(const ShotPlan& plan) {
  if (!plan.times.shutter_open()) return plan.frame;
  return 0.5 * (plan.times.open_s + plan.times.close_s) * plan.fps;
}

// The camera, its lens values and overrides where it stands while the shutter is open: the lens
// track's values at the frame, as Cycles syncs them, the focal length at the shutter's centre.
SceneCamera plan_camera(const Scene& scene, const RenderOptions& options, const ShotPlan& plan) {
  SceneCamera camera = choose_camera(scene, options.camera, plan.times.still_s());
  if (const std::optional<LensTrack>& track = camera.lens_track) {
    track->apply(plan.frame, camera.physical);
    if (track->tracks(CameraValue::kFocalLength))
      camera.physical.focal_length_mm = track->at(CameraValue::kFocalLength, centre_frame(plan));
  }
  options.camera_overrides.apply(camera);
  check_focus_beyond_focal_length(camera);
  return camera;
}

// Adaptive sampling: the command line's values, else the shot's (Cycles' use_adaptive_sampling,
// adaptive_threshold, adaptive_min_samples), else kDefaultAdaptiveThreshold. A shot's threshold
// of 0 with adaptive sampling on is Cycles' automatic one, max(0.001, 1 / samples)
// (intern/cycles/scene/integrator.cpp).
void plan_adaptive(const ShotSettings& shot, const RenderOptions& options, ShotPlan& plan) {
  AdaptiveRequest& request = plan.adaptive_request;
  request = {kDefaultAdaptiveThreshold, 0};
  if (shot.adaptive) {
    const ShotAdaptiveSampling& a = *shot.adaptive;
    request.threshold = !a.use            ? 0
                        : a.threshold > 0 ? a.threshold
                                          : std::max(0.001, 1.0 / plan.samples_per_pixel);
    request.min_samples = a.min_samples;
  }
  if (options.adaptive_threshold) request.threshold = *options.adaptive_threshold;
  if (options.adaptive_min_samples) request.min_samples = *options.adaptive_min_samples;
  plan.adaptive = adaptive_settings(request);
  if (plan.adaptive && options.reconstruction == Reconstruction::kSplat)
    throw UsageError(std::string(options.adaptive_threshold ? "--adaptive-threshold"
                                                            : "the shot's adaptive sampling") +
                     " with --reconstruction splat: a splatted sample reaches several pixels, so "
                     "no pixel can stop alone; use --reconstruction importance, or "
                     "--adaptive-threshold 0");
}

void plan_image(const ShotSettings& shot, const RenderOptions& options, ShotPlan& plan) {
  if (options.width.has_value() != options.height.has_value())
    throw UsageError("--res: give both width and height");
  std::tie(plan.width_px, plan.height_px) =
      options.width   ? std::pair{*options.width, *options.height}
      : shot.width_px ? std::pair{*shot.width_px, *shot.height_px}
                      : default_resolution(plan.camera);
  plan.samples_per_pixel = options.samples_per_pixel.value_or(kDefaultSamplesPerPixel);
  plan_adaptive(shot, options, plan);
  plan.pixel_aspect = shot.pixel_aspect.value_or(1.0);
  // A physical sensor integrates over the open shutter; an instantaneous one reports per second.
  const double open_s = plan.shutter_s.y - plan.shutter_s.x;
  plan.sensor = SensorResponse{options.sensor_model, open_s > 0 ? open_s : 1.0, options.iso};
}

// A zoom within the open shutter (core/render/zoom_in_shutter.h): the focal length's track at
// shutter open and close against the centre's, for Blender's perspective camera only, as Cycles
// (have_perspective_motion is for CAMERA_PERSPECTIVE); none when --focal-length replaces it.
std::optional<ZoomInShutter> plan_zoom(const ShotPlan& plan) {
  const SceneCamera& camera = plan.camera;
  constexpr CameraValue kFocal = CameraValue::kFocalLength;
  if (!plan.times.shutter_open() || !camera.lens_track || !camera.lens_track->tracks(kFocal) ||
      camera.origin(kFocal).typed() || camera.physical.projection != FB_PROJECTION_PERSPECTIVE ||
      camera.model)
    return std::nullopt;
  const auto setup_at = [&](double time_s) {
    PhysicalCamera c = camera.physical;
    c.focal_length_mm = camera.lens_track->at(kFocal, time_s * plan.fps);
    return make_camera_setup(c, plan.width_px, plan.height_px, plan.pixel_aspect);
  };
  return zoom_in_shutter(setup_at(plan.times.open_s), plan.camera_setup(),
                         setup_at(plan.times.close_s));
}

}  // namespace

namespace {

void append_setting(std::string& text, const std::string& key, const std::string& value) {
  text.append(text.find(':') == std::string::npos ? ":" : ",")
      .append(key)
      .append("=")
      .append(value);
}

}  // namespace

std::string PluginChoice::typed_text() const {
  std::string out = name;
  for (const auto& [key, value] : typed)
    append_setting(out, key, value);
  return out;
}

bool PluginChoice::typed_key(std::string_view key) const {
  return std::any_of(typed.begin(), typed.end(), [&](const auto& t) { return t.first == key; });
}

std::string PluginChoice::text() const {
  std::string out = typed_text();
  for (const NamedNumber& n : numbers)
    if (!typed_key(n.key)) append_setting(out, n.key, number_text(n.value));
  return out;
}

fb_camera_setup ShotPlan::camera_setup() const {
  return make_camera_setup(camera.physical, width_px, height_px, pixel_aspect, sensor);
}

ShotPlan plan_shot(const Scene& scene, const RenderOptions& options) {
  const ShotSettings& shot = scene.settings;
  ShotPlan plan;
  plan_times(shot, options, plan);
  plan.camera = plan_camera(scene, options, plan);
  plan_image(shot, options, plan);
  plan.zoom = plan_zoom(plan);
  plan.camera_model = choose_camera_model(options.camera_model, plan.camera, plan.sensor);
  plan.filter = choose_filter(options.filter, shot);
  plan.integrator = choose_integrator(options.integrator, options.passes);
  return plan;
}

std::pair<uint32_t, uint32_t> default_resolution(const SceneCamera& camera) {
  const double aspect = camera.intended_aspect.value_or(16.0 / 9.0);
  if (aspect >= 1.0)
    return {kDefaultLongSidePx,
            std::max<uint32_t>(1, uint32_t(std::lround(kDefaultLongSidePx / aspect)))};
  return {std::max<uint32_t>(1, uint32_t(std::lround(kDefaultLongSidePx * aspect))),
          kDefaultLongSidePx};
}

std::string planned_filter_text(const std::optional<std::string>& typed, const ShotSettings& shot) {
  return choose_filter(typed, shot).text();
}

std::optional<std::string> shot_filter_text(const ShotSettings& shot) {
  if (!shot.filter) return std::nullopt;
  return filter_for(*shot.filter).text();
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

}  // namespace fb
