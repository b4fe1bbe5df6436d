// Interrupted, checkpointed and resumed renders (docs/cli.md, "Interrupts and checkpoints"):
// whatever stops a render and wherever it is resumed from, the finished image is bit-identical
// to one rendered without a stop, because each pixel's samples are summed in sample order, with
// importance sampling, splatting and adaptive sampling.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <numbers>
#include <set>

#include "core/film/checkpoint.h"
#include "core/image/image_io.h"
#include "core/render/render_job.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

// A lit floor under an emissive square and a point light, seen by the default camera: every
// pixel's value depends on its own samples through light and BSDF sampling.
Scene lit_floor() {
  GltfBuilder gltf;
  const std::vector<uint32_t> square_indices = {0, 1, 2, 0, 2, 3};
  const auto square = [](float half) {
    return std::vector<Vec3f>{
        {-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
  };
  GltfBuilder::Node floor, lamp, light;
  const double s = std::sin(std::numbers::pi / 4), c = std::cos(std::numbers::pi / 4);
  floor.mesh = gltf.mesh(square(3), square_indices, gltf.material({0.7f, 0.6f, 0.5f}));
  floor.rotation = {-s, 0, 0, c};
  lamp.mesh = gltf.mesh(square(0.5f), square_indices, gltf.material({0, 0, 0}, {4, 4, 4}));
  lamp.translation = {0, 2, 0};
  lamp.rotation = {s, 0, 0, c};
  light.light = gltf.point_light({1, 0.8f, 0.6f}, 683.0);
  light.translation = {1, 1, 1};
  gltf.node(floor), gltf.node(lamp), gltf.node(light);
  Diagnostics diagnostics;
  return import_gltf(gltf.write(test::scratch_dir() / "interrupt.gltf"), diagnostics);
}

RenderOptions options(uint32_t spp) {
  RenderOptions o;
  o.width = 70, o.height = 40, o.samples_per_pixel = spp, o.seed = 3;  // tiles cut at the edges
  o.show_progress = false;
  return o;
}

// Stops the render at the n-th time the render loop offers a checkpoint, keeping the film.
struct StopAtCheckpoint {
  int remaining;
  std::atomic<bool> cancel{false};
  RenderControl control() {
    RenderControl c;
    c.cancel = &cancel;
    c.checkpoint_every = std::chrono::steady_clock::duration::zero();  // at every chance
    c.checkpoint = [this](const Film&, const SamplingState&) {
      if (--remaining == 0) cancel = true;
    };
    return c;
  }
};

TEST(Interrupt, ACancelledRenderReportsEachPixelsSamplesAndResumesBitIdentically) {
  const Scene scene = lit_floor();
  const RenderJob job(scene, options(24), test::loader());
  const RenderResult whole = job.run();
  EXPECT_EQ(whole.fewest_samples, 24u);
  EXPECT_EQ(whole.most_samples, 24u);
  EXPECT_EQ(whole.image.channels.size(), 3u);  // a finished render has no "samples" channel

  Film film = job.make_film();
  SamplingState state;
  StopAtCheckpoint stop{5};
  const RenderResult part = job.run(film, state, stop.control());
  ASSERT_TRUE(part.stats.interrupted);
  EXPECT_LT(part.fewest_samples, 24u);
  EXPECT_GT(part.most_samples, 0u);
  ASSERT_EQ(part.image.channels.back(), "samples");
  uint64_t counted = 0;
  for (uint32_t y = 0; y < 40; ++y)
    for (uint32_t x = 0; x < 70; ++x) {
      const float samples = part.image.at(x, y, 3);
      EXPECT_EQ(samples, float(film.sample_count(x, y)));
      counted += uint64_t(samples);
    }
  EXPECT_EQ(counted, part.stats.samples);  // the AOV counts exactly the samples taken

  // Through a checkpoint file, as the command line resumes.
  const auto file = test::scratch_dir() / "interrupt.checkpoint.exr";
  write_checkpoint(film, state, "key", file);
  Film resumed = job.make_film();
  SamplingState resumed_state = job.make_sampling_state();
  read_checkpoint(file, "key", 24, kTileSize, resumed, resumed_state);
  const RenderResult rest = job.run(resumed, resumed_state);
  EXPECT_FALSE(rest.stats.interrupted);
  EXPECT_EQ(rest.stats.samples + part.stats.samples, whole.stats.samples);
  EXPECT_EQ(rest.image.pixels, whole.image.pixels);
}

TEST(Interrupt, CheckpointsTakenOnTheWayChangeNothing) {
  const Scene scene = lit_floor();
  const RenderJob job(scene, options(9), test::loader());  // 9: the last pass is not a doubling
  const RenderResult whole = job.run();
  Film film = job.make_film();
  SamplingState state;
  int checkpoints = 0;
  RenderControl control;
  control.checkpoint = [&](const Film&, const SamplingState&) { ++checkpoints; };  // every chance
  const RenderResult again = job.run(film, state, control);
  EXPECT_GT(checkpoints, 4);
  EXPECT_EQ(again.image.pixels, whole.image.pixels);
}

// --preview: the loop's preview hook, called at every chance, resolves the image so far without
// touching the film. With splatting the samples so far live in the splat tiles only, so a preview
// that missed them would be black; one that added them into the render's own film would change
// the final image.
TEST(Interrupt, PreviewsShowTheImageSoFarAndChangeNothing) {
  const Scene scene = lit_floor();
  for (const Reconstruction reconstruction :
       {Reconstruction::kImportance, Reconstruction::kSplat}) {
    RenderOptions o = options(9);
    o.reconstruction = reconstruction;
    o.filter = "gaussian";
    const RenderJob job(scene, o, test::loader());
    const RenderResult whole = job.run();
    Film film = job.make_film();
    SamplingState state = job.make_sampling_state();
    int previews = 0;
    float brightest_preview = 0;
    RenderControl control;
    control.preview = [&](const Film& f, const SamplingState& s) {
      const Image image = job.image_so_far(f, s);
      ASSERT_EQ(image.pixels.size(), whole.image.pixels.size());
      for (const float value : image.pixels) {
        ASSERT_TRUE(std::isfinite(value));
        brightest_preview = std::max(brightest_preview, value);
      }
      ++previews;
    };
    const RenderResult again = job.run(film, state, control);
    EXPECT_GT(previews, 4) << reconstruction_name(reconstruction);
    EXPECT_GT(brightest_preview, 0.0f) << reconstruction_name(reconstruction);
    EXPECT_EQ(again.image.pixels, whole.image.pixels) << reconstruction_name(reconstruction);
  }
}

// A render nothing can stop takes one pass over each tile (render_loop.h); one that a signal could
// stop takes the doubling passes. The sums are formed in the same order either way: the images
// must be bit-identical, with importance sampling and with splatting (whose tiles' sums reach
// their neighbours' pixels).
TEST(Interrupt, OnePassAndDoublingPassesGiveTheSameImage) {
  const Scene scene = lit_floor();
  for (const Reconstruction reconstruction :
       {Reconstruction::kImportance, Reconstruction::kSplat}) {
    RenderOptions o = options(11);  // passes end at 1, 2, 4, 8 and 11
    o.reconstruction = reconstruction;
    o.filter = "gaussian";
    const RenderJob job(scene, o, test::loader());
    const RenderResult one_pass = job.run();
    const std::atomic<bool> never{false};
    RenderControl control;
    control.cancel = &never;
    Film film = job.make_film();
    SamplingState state;
    const RenderResult passes = job.run(film, state, control);
    EXPECT_EQ(passes.stats.samples, one_pass.stats.samples);
    EXPECT_EQ(passes.image.pixels, one_pass.image.pixels) << reconstruction_name(reconstruction);
  }
}

TEST(Interrupt, CheckpointsOfAnotherRenderOrAnImpossibleStateAreRefused) {
  const Scene scene = lit_floor();
  const RenderJob job(scene, options(8), test::loader());
  Film film = job.make_film();
  SamplingState state;
  StopAtCheckpoint stop{3};
  job.run(film, state, stop.control());
  const auto file = test::scratch_dir() / "refused.checkpoint.exr";
  write_checkpoint(film, state, "this render", file);
  const auto refusal = [&](const std::string& key, uint32_t spp) -> std::string {
    Film target = job.make_film();
    SamplingState target_state = job.make_sampling_state();
    try {
      read_checkpoint(file, key, spp, kTileSize, target, target_state);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_EQ(refusal("this render", 8), "accepted");
  EXPECT_NE(refusal("another render", 8).find("written for another render"), std::string::npos);
  EXPECT_NE(refusal("this render", 1).find("cannot have left"), std::string::npos);
  // Sample counts that differ within one tile: a state no render leaves.
  film.sample_counts()[1] += 1;
  write_checkpoint(film, state, "this render", file);
  EXPECT_NE(refusal("this render", 8).find("pixel 1,0 has"), std::string::npos);
  // An image is no checkpoint.
  write_images(job.run().image, {file}, {});
  EXPECT_NE(refusal("this render", 8).find("not a filmback checkpoint"), std::string::npos);
  // A checkpoint of an earlier filmback (version 1: the film alone) names the file and versions.
  ImageMetadata version_1;
  version_1.ints = {{"filmback/checkpoint_version", 1}};
  version_1.strings = {{"filmback/checkpoint_key", "this render"}};
  write_images(job.run().image, {file}, version_1);
  const std::string old = refusal("this render", 8);
  EXPECT_NE(old.find(file.string() + ": cannot resume from this checkpoint: it is a version 1 "
                                     "checkpoint, this filmback reads 2"),
            std::string::npos)
      << old;
}

// Interrupted at the `stop_at`-th checkpoint offered, saved through a checkpoint file, loaded into
// a fresh film and state and finished: the film and the per-pixel counts of the whole render.
struct ResumedRender {
  RenderResult whole, stopped, rest;
  std::vector<uint32_t> whole_counts, rest_counts;
  size_t converged_at_stop = 0;  // pixels the checkpoint's convergence map had stopped
};

ResumedRender resume_through_file(const RenderJob& job, const std::string& name,
                                  const std::function<bool(const SamplingState&)>& stop_now) {
  ResumedRender r;
  Film whole = job.make_film();
  r.whole = job.run(whole);
  r.whole_counts.assign(whole.sample_counts(), whole.sample_counts() + whole.pixel_count());
  Film film = job.make_film();
  SamplingState state;
  std::atomic<bool> cancel{false};
  RenderControl control;
  control.cancel = &cancel;
  control.checkpoint = [&](const Film&, const SamplingState& s) {
    if (stop_now(s)) cancel = true;
  };
  r.stopped = job.run(film, state, control);
  const auto file = test::scratch_dir() / (name + ".checkpoint.exr");
  write_checkpoint(film, state, "key", file);
  if (state.convergence)
    r.converged_at_stop =
        size_t(std::count(state.convergence->converged_flags(),
                          state.convergence->converged_flags() + film.pixel_count(), uint8_t(1)));
  Film resumed = job.make_film();
  SamplingState resumed_state = job.make_sampling_state();
  read_checkpoint(file, "key", job.samples_per_pixel(), kTileSize, resumed, resumed_state);
  r.rest = job.run(resumed, resumed_state);
  r.rest_counts.assign(resumed.sample_counts(), resumed.sample_counts() + resumed.pixel_count());
  return r;
}

// Splatting: the tiles' sums, which reach their neighbours' pixels and are added to the film only
// at the end, are saved in the checkpoint and resumed exactly.
TEST(Interrupt, ASplattedRenderResumesFromItsCheckpointBitIdentically) {
  const Scene scene = lit_floor();
  RenderOptions o = options(12);
  o.reconstruction = Reconstruction::kSplat;
  o.filter = "gaussian:radius=2.5";
  const RenderJob job(scene, o, test::loader());
  int offered = 0;
  const ResumedRender r =
      resume_through_file(job, "splat", [&](const SamplingState&) { return ++offered == 5; });
  ASSERT_TRUE(r.stopped.stats.interrupted);
  EXPECT_LT(r.stopped.fewest_samples, 12u);
  EXPECT_FALSE(r.rest.stats.interrupted);
  EXPECT_EQ(r.rest.stats.samples + r.stopped.stats.samples, r.whole.stats.samples);
  EXPECT_EQ(r.rest.image.pixels, r.whole.image.pixels);
}

// Adaptive sampling: stopped after two convergence checks, with some pixels converged and others
// not, resumed with the saved half buffer and flags; the checks still to come are made at the
// same counts. Pixels converge at several counts, so a lost or repeated check would show.
TEST(Interrupt, AnAdaptiveRenderResumesFromItsCheckpointBitIdentically) {
  const Scene scene = lit_floor();
  RenderOptions o = options(64);
  o.adaptive_threshold = 0.05, o.adaptive_min_samples = 16;  // checks at 16, 32 and 48
  const RenderJob job(scene, o, test::loader());
  const ResumedRender r = resume_through_file(job, "adaptive", [](const SamplingState& s) {
    return s.convergence->checked_samples() >= 32;
  });
  ASSERT_TRUE(r.stopped.stats.interrupted);
  EXPECT_GT(r.converged_at_stop, 0u);
  EXPECT_LT(r.converged_at_stop, r.whole_counts.size());
  const std::set<uint32_t> counts(r.whole_counts.begin(), r.whole_counts.end());
  EXPECT_GE(counts.size(), 3u) << "pixels should converge at several counts";
  EXPECT_EQ(r.rest.stats.samples + r.stopped.stats.samples, r.whole.stats.samples);
  EXPECT_EQ(r.rest_counts, r.whole_counts);
  EXPECT_EQ(r.rest.image.pixels, r.whole.image.pixels);
}

}  // namespace
}  // namespace fb
