// The shot plan: one pure step from a scene, its shot settings and the command line to typed
// choices: the camera posed at the shot's time, the resolution, samples, times, shutter curve and
// sensor, and which camera, filter and integrator plugins render it with which values. Each value
// keeps its origin (core/scene/value_origin.h), so that `filmback info` can print it and an error
// names it. The plan loads nothing and reads no file; a RenderJob loads what it names
// (core/render/render_job.h). This file's .cpp holds the one table from a shot's projection and
// pixel filter to plugins (docs/architecture.md, "The shot plan").
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <filmback/render_passes.h>
#include <filmback/vec.h>

#include "core/film/adaptive_sampling.h"
#include "core/film/film.h"
#include "core/render/light_choice.h"
#include "core/render/sampler.h"
#include "core/render/shutter.h"
#include "core/render/zoom_in_shutter.h"
#include "core/scene/scene.h"
#include "core/scene/value_origin.h"
#include "core/subdiv/refine_scene.h"

namespace fb {

// Values typed on the command line that replace the scene camera's (docs/cli.md).
struct CameraOverrides {
  std::optional<double> focal_length_mm;
  std::optional<double> fstop;  // as fstop_from gives it: HUGE_VAL is a pinhole
  std::optional<double> focus_distance_m;
  std::optional<Vec2d> sensor_mm;  // width, height
  std::optional<uint32_t> sensor_fit;
  std::optional<Vec2d> shift;
  // Replaces the camera's values, each with the option as its origin.
  void apply(SceneCamera& camera) const;
};

struct RenderOptions {
  std::optional<uint32_t> width, height;  // both or neither
  std::optional<uint32_t> samples_per_pixel;
  std::optional<std::string> camera;        // a scene camera by name
  std::optional<std::string> camera_model;  // "NAME[:k=v,...]": overrides the projection's plugin
  std::optional<std::string> filter;        // "NAME[:k=v,...]"
  std::optional<std::string> integrator;    // "NAME[:k=v,...]"
  // --passes: Blender's render passes to write beside the beauty (filmback/render_passes.h), as
  // the integrator's `passes` parameter; none: the beauty alone, R, G, B as before.
  std::vector<std::string> passes;
  // --view-layer: the layer the passes' channels are named after, "<view_layer>.<Pass>.<Ch>":
  // Blender's view layer the image goes to (filmback/render_passes.h names Blender's default).
  std::string view_layer = kViewLayer;
  // --cryptomatte-levels: the ranks each Cryptomatte pass writes per pixel (Blender's Levels);
  // none: Blender's default (core/film/cryptomatte.h).
  std::optional<uint32_t> cryptomatte_levels;
  std::optional<Rgb> background;
  CameraOverrides camera_overrides;
  std::optional<Vec2d> shutter_s;            // open, close, relative to the frame's time
  std::optional<std::string> shutter_curve;  // "box", "trapezoid[:ramp=R]", "table:values=[...]"
  // --rolling-shutter: a duration in [0, 1], or none (0 rows) for a global shutter; replaces
  // the shot's.
  std::optional<std::optional<RollingShutter>> rolling_shutter;
  std::optional<double> frame, fps;
  uint32_t sensor_model = FB_SENSOR_SIMPLE;
  double iso = 100.0;
  uint64_t seed = 0;
  SamplerKind sampler = kDefaultSampler;                        // docs/sampling.md
  Reconstruction reconstruction = Reconstruction::kImportance;  // docs/filters.md
  SubdivMode subdiv = SubdivMode::kRender;                      // --subdiv (docs/cli.md)
  LightSelection light_selection = LightSelection::kAuto;       // --light-sampler (docs/cli.md)
  // --adaptive-threshold (0: off) and --adaptive-min-samples (0: automatic); each replaces the
  // shot's (docs/sampling.md, "Adaptive sampling").
  std::optional<double> adaptive_threshold;
  std::optional<uint32_t> adaptive_min_samples;
  bool show_progress = true;
  // --progress-every: plain progress lines at this interval whatever stderr is; zero: the
  // default (a bar on a terminal, a line every 10 s otherwise).
  std::chrono::steady_clock::duration progress_every{};
  // Texture lookups filtered by each ray's footprint (docs/architecture.md, "Texture
  // filtering"); false reads every texture at its finest level, as before issue 17.
  bool texture_footprint = true;
  // What the render may hold at its peak (core/render/memory_estimate.h); none: half of the
  // machine's memory.
  std::optional<uint64_t> memory_limit_bytes;
};

// Documented defaults (docs/cli.md).
constexpr uint32_t kDefaultLongSidePx = 1280;
constexpr uint32_t kDefaultSamplesPerPixel = 64;
// Adaptive sampling when neither the command line nor the shot says (docs/benchmarks.md,
// "Adaptive sampling", measured the choice): off.
constexpr double kDefaultAdaptiveThreshold = 0;
constexpr double kDefaultFps = 24;  // Blender's; matters only when the frame is not 0

// One plugin as the plan chose it.
struct PluginChoice {
  std::string name;
  // key=value pairs typed with the name in an option ("--filter gaussian:sigma=1"), in order.
  std::vector<std::pair<std::string, std::string>> typed;
  // Values from the shot. Each sets the parameter of its name when the plugin declares one and
  // `typed` does not set it: a shot's lens values reach any camera plugin with a parameter of
  // that name (docs/plugins.md, "Camera parameters").
  std::vector<NamedNumber> numbers;
  // Why this plugin: the option that named it, the shot value that called for it, or a default.
  // Errors about the plugin or its values name it.
  ValueOrigin origin;
  // "gaussian:radius=2.25,sigma=0.375": the typed pairs, then the shot's numbers, for the plan
  // line, the image metadata and messages (the render passes the values as they are).
  std::string text() const;
  std::string typed_text() const;  // the name and the typed pairs only: what the user wrote
  bool typed_key(std::string_view key) const;  // whether `typed` sets `key`
};

struct ShotPlan {
  SceneCamera camera;  // posed at the still time, its lens track evaluated, options applied
  uint32_t width_px = 0, height_px = 0, samples_per_pixel = 0;
  std::optional<AdaptiveSettings> adaptive;  // none: every pixel takes every sample
  AdaptiveRequest adaptive_request;          // what it was derived from, for the plan line
  double pixel_aspect = 1;                   // pixel width / height
  double frame = 0, fps = kDefaultFps;
  Vec2d shutter_s;  // open, close, relative to the frame's time
  ShotTimes times;  // the shutter and the frame's time on the scene's timeline, s
  ShutterCurve shutter_curve;
  std::optional<RollingShutter> rolling_shutter;  // only while the shutter is open
  std::optional<ZoomInShutter> zoom;              // the focal length's track within the shutter
  SensorResponse sensor;
  PluginChoice camera_model, filter, integrator;

  // The host's part of the camera (pose aside): projection, sensor, resolution, and, for plugins
  // built before camera parameters, the lens (plugin_abi.h).
  fb_camera_setup camera_setup() const;
};

// Throws UsageError for options that contradict each other or the shot, InputError (naming the
// file and JSON path) for scene values no plugin can take. Reads nothing but its arguments.
ShotPlan plan_shot(const Scene& scene, const RenderOptions& options);

// The image size a render gets without --res: the long side kDefaultLongSidePx at the shot's
// intended aspect (16:9 when the scene does not say).
std::pair<uint32_t, uint32_t> default_resolution(const SceneCamera& camera);

// The projection of Blender's that the chosen camera plugin makes (FB_PROJECTION_PERSPECTIVE for
// the pinhole and the thin lens, FB_PROJECTION_ORTHOGRAPHIC), for what the host projects points
// by itself (the Vector pass); none for any other plugin.
std::optional<uint32_t> blender_projection(const PluginChoice& camera_model);

// The filter a render with `typed` (--filter) uses on this shot, as PluginChoice::text() says it:
// "gaussian:radius=2.25,sigma=0.375" for a shot's Gaussian of width 1.5 px.
std::string planned_filter_text(const std::optional<std::string>& typed, const ShotSettings& shot);
// The shot's own pixel filter so; nothing when the shot names none.
std::optional<std::string> shot_filter_text(const ShotSettings& shot);

}  // namespace fb
