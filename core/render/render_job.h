// A RenderJob carries out a shot plan (core/render/shot_plan.h): it loads just the plugins the plan
// names, builds what the scene needs and nothing more, and runs the render loop. Everything that
// can fail on bad input fails in the constructor, before any pixel is traced and before any
// output file exists.
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
#include "core/render/shot_plan.h"
#include "core/scene/scene.h"
#include "core/subdiv/refine_scene.h"

namespace fb {

struct GeometryCounts;  // core/render/memory_estimate.h

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
  // cryptomatte/<key>/... (CryptomatteFilm::metadata), when --passes asks for Cryptomatte.
  std::vector<std::pair<std::string, std::string>> cryptomatte_metadata;
};

// Cycles' Film > Exposure: a gain on the rendered radiance, colour channels only. What a render
// and `filmback merge` apply to the resolved film.
void apply_film_exposure(Image& image, double gain);

class RenderJob {
 public:
  RenderJob(const Scene& scene, const RenderOptions& options, const PluginLoader& loader);
  ~RenderJob();
  // Not copied or moved: the time sampling points into the plan's shutter curve.
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  RenderChoices choices() const;
  std::string plan() const;  // one line: what was chosen and why
  // An empty film of this render's size and channels (or one to load a checkpoint into).
  Film make_film() const;
  // An empty sampling state shaped for this render (splat tiles' slots, the convergence map), to
  // load a checkpoint into (core/film/checkpoint.h).
  SamplingState make_sampling_state() const;
  // Renders into `film` and `state`, continuing from the samples they already hold (docs/cli.md,
  // "Interrupts and checkpoints"), and resolves the film. With `crop`, only that part of the frame
  // (docs/cli.md, "Parts of a render"; RenderInputs::crop): its pixels hold the whole render's
  // sums, and with splatting `state` keeps the part's splat tiles for its partial film. A whole
  // render that ends has added its splat tiles to the film: they are freed before it is resolved.
  RenderResult run(Film& film, SamplingState& state, const RenderControl& control = {},
                   const std::optional<PixelRect>& crop = std::nullopt) const;
  RenderResult run(Film& film) const;
  RenderResult run() const;
  // The image a render paused between two samples (RenderControl's checkpoint or preview hook)
  // holds so far, resolved as run() resolves the final one: with splatting, the splat tiles are
  // added to a copy of `film`, which keeps its own sums for the render to go on.
  Image image_so_far(const Film& film, const SamplingState& state) const;
  // The pixels a part with `crop` renders and its checkpoint holds: the crop, with adaptive
  // sampling its apron (part_region), grown to whole tiles.
  PixelRect part_tiles(const PixelRect& crop) const;
  ImageMetadata metadata(const RenderResult& result) const;

  const ShotPlan& shot_plan() const { return plan_; }
  const SceneCamera& camera() const { return plan_.camera; }
  uint32_t width() const { return plan_.width_px; }
  uint32_t height() const { return plan_.height_px; }
  uint32_t samples_per_pixel() const { return plan_.samples_per_pixel; }
  Reconstruction reconstruction() const { return options_.reconstruction; }

 private:
  struct Plugins;
  void load_plugins(const PluginLoader& loader);
  void build_geometry();       // subdivision refined, memory checked, geometry and lights
  void choose_time_samples();  // sets time_reason_ and the time plugins_ need
  void make_scene_table();     // what the integrator sees of the scene
  RenderInputs inputs(const std::optional<PixelRect>& crop) const;  // what render_image is given
  Image resolve(const Film& film) const;  // the film's mean, with the scene's film exposure
  // The film's, and these triangles' with their texture coordinates and tangents.
  void check_memory_budget(const GeometryCounts& geometry) const;
  const Scene& scene_;
  RenderOptions options_;
  ShotPlan plan_;
  std::string camera_reason_;
  std::string time_reason_;
  std::unique_ptr<Plugins> plugins_;
};

}  // namespace fb
