// The render loop: the measurement equation term by term. For every pixel sample it draws a
// filter offset (the integral over R^2 with h), asks the camera for a ray and its weight (the
// aperture integral and the cos^4/f^2 factor, when the camera models them), asks the integrator for
// the radiance L along it, and hands the filter-weighted value to the film.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>

#include <filmback/plugin_abi.h>

#include "core/accel/render_geometry.h"
#include "core/film/adaptive_sampling.h"
#include "core/film/cryptomatte.h"
#include "core/film/film.h"
#include "core/film/motion_vector_film.h"
#include "core/film/pixel_rect.h"
#include "core/film/sampling_state.h"
#include "core/film/splat_tiles.h"
#include "core/math/transform.h"
#include "core/plugin/instances.h"
#include "core/render/global_medium_segment.h"
#include "core/render/light_sampler.h"
#include "core/render/motion.h"
#include "core/render/motion_vectors.h"
#include "core/render/progress.h"
#include "core/render/sampler.h"
#include "core/render/tile_size.h"
#include "core/render/zoom_in_shutter.h"

namespace fb {

struct RenderInputs {
  const CameraInstance& camera;
  const FilterInstance& filter;
  const IntegratorInstance& integrator;
  const RenderGeometry& geometry;
  const LightSampler& lights;
  const fb_scene& scene;
  Transform render_from_camera;  // a rotation: render space is centred on the camera
  uint32_t samples_per_pixel;
  SamplerKind sampler;
  uint64_t seed;
  Reconstruction reconstruction = Reconstruction::kImportance;
  // Time (docs/camera-model.md, "Time and motion"): drawn only when something moves while the
  // shutter is open; a moving camera places each ray at its own time.
  TimeSampling time = {};
  const CameraPath* camera_path = nullptr;
  // A zoom while the shutter is open: each raster position scaled for its ray's time before the
  // camera plugin maps it (core/render/zoom_in_shutter.h). Only with time samples.
  const ZoomInShutter* zoom = nullptr;
  // Adaptive sampling (core/film/adaptive_sampling.h): none, every pixel takes every sample.
  // Importance reconstruction only: a splatted sample reaches several pixels.
  std::optional<AdaptiveSettings> adaptive = std::nullopt;
  double exposure = 1;  // the gain the image gets (Cycles' Film > Exposure): the error sees it
  // Texture lookups filtered by each ray's footprint (core/texture/ray_footprint.h): the camera
  // is asked for each ray's neighbours one pixel right and down, at twice the camera's cost, so
  // only scenes with image textures turn it on. Off: the finest level, as before.
  bool texture_footprint = false;
  // The scene's global media (core/render/global_medium_segment.h); none without them.
  const RenderMedia* media = nullptr;
  // A part of the render (docs/cli.md, "Parts of a render"): only the tiles it needs are sampled,
  // each pixel with exactly the samples of the whole render (the sampler is seeded per pixel of
  // the whole sample domain). Importance: every tile that meets part_region(crop) (whole tiles,
  // so that each ray batch is the whole render's; with adaptive sampling an apron around the crop,
  // so that its pixels converge as in the whole render). Splatting: every tile of the sample
  // domain whose first film pixel (clamped to the film) lies in the crop, so that the parts of a
  // frame share out its tiles. None: the whole frame.
  std::optional<PixelRect> crop = std::nullopt;
  // Cryptomatte (core/film/cryptomatte.h): each sample's camera ray is intersected once more for
  // the object and material it meets, which go here with the sample's filter weight. Importance
  // reconstruction only. None: nothing more is traced.
  CryptomatteFilm* cryptomatte = nullptr;
  // Vector (core/render/motion_vectors.h): the point each sample's camera ray meets (the same
  // second intersection as Cryptomatte's, once for both) and its motion, into the film with the
  // sample's filter weight; misses add nothing. Both or neither. Importance reconstruction only.
  const MotionVectors* motion_vectors = nullptr;
  MotionVectorFilm* motion_vector_film = nullptr;
};

struct RenderStats {
  double seconds = 0;
  uint64_t samples = 0;
  uint64_t rays = 0;
  uint64_t dropped_samples = 0;  // non-finite values kept out of the film
  bool interrupted = false;      // RenderControl::cancel stopped it: pixels may lack samples
  // Per 16x16 tile of the film, row by row: the seconds spent sampling it, for cost-balanced parts
  // (docs/distributed.md). Splatting: a sample-domain tile's time goes to the film tile of its
  // first film pixel, clamped to the film.
  std::vector<double> tile_seconds;
};

// What may stop or pause a render from outside (docs/cli.md, "Interrupts and checkpoints").
struct RenderControl {
  // When it becomes true (a signal handler sets it), every tile stops before its next sample
  // index: the render returns within about one sample of a tile.
  const std::atomic<bool>* cancel = nullptr;
  // Called with the film and the sampling state at a consistent state (every pixel's sums cover
  // exactly its recorded sample count, every splat tile's its samples) at least `checkpoint_every`
  // after the start or the last call.
  std::function<void(const Film&, const SamplingState&)> checkpoint;
  std::chrono::steady_clock::duration checkpoint_every{};
  // Called the same way, at least `preview_every` apart: the live image (--preview). Its own
  // clock, so that a preview every second does not make checkpoints that often.
  std::function<void(const Film&, const SamplingState&)> preview;
  std::chrono::steady_clock::duration preview_every{};
};

// Renders into `film` and `state` on the calling thread's TBB arena, in passes of doubling sample
// counts over all tiles when `control` can stop the render (a cancel flag, checkpoints or
// previews), else each tile's samples in a row, while its part of the scene is in the core's cache
// (with adaptive sampling: after its minimum, passes of kAdaptiveStep samples, each followed by the
// convergence check; pixels that converged take no more samples and keep their own count in the
// film). A film and state that already hold samples (a resumed checkpoint: Film::sample_count per
// tile, each splat tile's samples, the convergence map and its last check) are continued from
// there; each pixel's samples are still summed in sample order and each check made once, at its
// sample count, so the image is bit-identical to an uninterrupted render. `progress` counts pixel
// samples. `state` is shaped by prepare_sampling_state; with splatting its tiles are added to the
// film when the render ends (or is interrupted) and stay there (a part writes them:
// core/film/partial_film.h).
RenderStats render_image(const RenderInputs& inputs, Film& film, SamplingState& state,
                         const RenderControl& control, Progress* progress);

// Gives `state` what a render of `inputs` into a width x height film keeps beside it: a slot per
// splat tile when splatting, the convergence map with adaptive sampling. What it already holds (a
// state to load a checkpoint into, or loaded) is kept.
void prepare_sampling_state(const RenderInputs& inputs, uint32_t width, uint32_t height,
                            SamplingState& state);

// Pixel samples of a render: the sample domain's pixels (the film, and around it the filter's reach
// when splatting) that inputs.crop takes, times the samples per pixel.
uint64_t sample_count(const RenderInputs& inputs, uint32_t width, uint32_t height);

// The pixels a part's importance-sampled render writes: `crop` grown to whole tiles, within the
// film; what its checkpoint holds.
PixelRect whole_tiles_around(const PixelRect& crop, uint32_t width, uint32_t height);

// The pixels a part with `crop` samples, before whole tiles: with adaptive sampling, `crop` and an
// apron of adaptive_check_count pixels around it, within the film (a pixel's convergence after k
// checks depends on pixels up to k away); else `crop`. Only the crop's pixels go into the partial
// film: the apron's may have converged otherwise than in the whole render.
PixelRect part_region(const PixelRect& crop, const std::optional<AdaptiveSettings>& adaptive,
                      uint32_t samples_per_pixel, uint32_t width, uint32_t height);

}  // namespace fb
