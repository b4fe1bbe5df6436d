// A RenderJob decides what a scene needs and nothing more, loads just those plugins, and runs
// the render loop. Everything that can fail on bad input fails in the constructor, before any
// pixel is traced and before any output file exists.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <filmback/vec.h>

#include "core/image/image.h"
#include "core/image/image_io.h"
#include "core/plugin/loader.h"
#include "core/render/render_loop.h"
#include "core/scene/scene.h"
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
  std::optional<Rgb> background;
  CameraOverrides camera_overrides;
  std::optional<Vec2d> shutter_s;            // open, close, relative to the frame's time
  std::optional<std::string> shutter_curve;  // "box", "trapezoid[:ramp=R]", "table:values=[...]"
  std::optional<double> frame, fps;
  uint32_t sensor_model = FB_SENSOR_SIMPLE;
  double iso = 100.0;
  uint64_t seed = 0;
  SamplerKind sampler = kDefaultSampler;                        // docs/sampling.md
  Reconstruction reconstruction = Reconstruction::kImportance;  // docs/filters.md
  SubdivMode subdiv = SubdivMode::kRender;                      // --subdiv (docs/cli.md)
  bool show_progress = true;
  // What the render may hold at its peak (core/render/memory_estimate.h); none: half of the
  // machine's memory.
  std::optional<uint64_t> memory_limit_bytes;
};

// Documented defaults (docs/cli.md).
constexpr uint32_t kDefaultLongSidePx = 1280;
constexpr uint32_t kDefaultSamplesPerPixel = 64;
constexpr const char* kDefaultFilter = "gaussian";
constexpr const char* kDefaultIntegrator = "path";
constexpr double kDefaultFps = 24;  // Blender's; matters only when the frame is not 0

// The image size a render gets without --res: the long side kDefaultLongSidePx at the shot's
// intended aspect (16:9 when the scene does not say).
std::pair<uint32_t, uint32_t> default_resolution(const SceneCamera& camera);

// The shot's pixel filter as the filter plugin it renders with, "gaussian:radius=2.25,sigma=0.375",
// for display and comparison only (the render passes the values typed); nothing when the shot
// names none.
std::optional<std::string> shot_filter_text(const ShotSettings& shot);

// What a RenderJob chose and why, as its plan line says it (docs/cli.md, "--stats-json").
struct RenderChoices {
  std::string camera, camera_source;  // the scene camera and where it came from
  std::string camera_model, lens;     // the camera plugin, and the lens it models
  std::string filter, reconstruction, integrator, sampler;
  std::string time;         // whether and why time is sampled
  std::string subdivision;  // how subdivision surfaces were refined; empty: none
  std::string materials;    // the material models the geometry uses
  uint64_t triangles = 0, lights = 0, emissive_triangles = 0;
};

struct RenderResult {
  Image image;  // an interrupted render adds a channel "samples": each pixel's sample count
  RenderStats stats;
  uint32_t fewest_samples = 0, most_samples = 0;  // over the pixels
};

class RenderJob {
 public:
  RenderJob(const Scene& scene, const RenderOptions& options, const PluginLoader& loader);
  ~RenderJob();

  RenderChoices choices() const;
  std::string plan() const;  // one line: what was chosen and why
  // An empty film of this render's size and channels (or one to load a checkpoint into).
  Film make_film() const;
  // Renders into `film`, continuing from the samples it already holds (docs/cli.md, "Interrupts
  // and checkpoints"), and resolves it.
  RenderResult run(Film& film, const RenderControl& control = {}) const;
  RenderResult run() const;
  ImageMetadata metadata(const RenderResult& result) const;

  const SceneCamera& camera() const { return camera_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t samples_per_pixel() const { return spp_; }

 private:
  struct Plugins;
  void choose_time_samples(const Scene& scene);  // sets time_reason_ and the time plugins_ need
  // The film's, and these triangles' with their texture coordinates and tangents.
  void check_memory_budget(double triangles, double texturing) const;
  const Scene& scene_;
  RenderOptions options_;
  SceneCamera camera_;
  uint32_t width_ = 0, height_ = 0, spp_ = 0;
  std::string camera_reason_;
  Vec2d shutter_s_;  // open, close, relative to the frame's time
  double frame_ = 0, fps_ = kDefaultFps;
  double pixel_aspect_ = 1.0;  // pixel width / height
  ShotTimes times_;            // the shutter and the frame's time on the scene's timeline, s
  std::string time_reason_;
  SensorResponse sensor_;
  std::unique_ptr<Plugins> plugins_;
};

}  // namespace fb
