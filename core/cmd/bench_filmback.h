// filmback's side of `filmback bench`: one scene imported once, its references, and every
// configuration at each sample count, each render through its own RenderJob.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/cmd/bench_types.h"
#include "core/image/image.h"
#include "core/plugin/loader.h"
#include "core/render/render_job.h"
#include "core/scene/scene.h"

namespace fb {

class FilmbackBench {
 public:
  // Imports `scene_file` (what filmback reads: a Blender shot's export) and makes the references,
  // or reads `reference_file` instead; work files (the references as EXR) go to `work`.
  FilmbackBench(const std::string& name, const std::filesystem::path& scene_file,
                const std::optional<std::filesystem::path>& reference_file,
                const BenchSettings& settings, const PluginLoader& loader,
                const std::filesystem::path& work);

  // Every configuration at `spp`, a row each in report().
  void render(uint32_t spp);

  // The report, with the memory the scene took and the median construction time; call once,
  // after the last render.
  SceneReport finish();

  // R, G, B, per BenchSettings::filters entry (a reference given as a file has no halves).
  const AveragedReference& reference(size_t filter) const { return references_[filter]; }
  const ReferenceNote& reference_note(size_t filter) const { return report_.references[filter]; }
  // The first filter that is the scene's own pixel filter (the one Cycles renders a Blender shot
  // with), if any.
  std::optional<size_t> shot_filter() const { return shot_filter_; }

  // From now on, the configurations with the shot's pixel filter are also measured against
  // Cycles' reference (`cycles` must outlive the renders), beside their own.
  void measure_against_cycles(const AveragedReference& cycles, const ReferenceNote& note);

 private:
  struct Timed;
  // `adaptive_threshold` replaces the shot's (0: off), so that every row says what it measured.
  RenderOptions options(uint32_t spp, SamplerKind sampler, const std::optional<std::string>& filter,
                        uint64_t seed, double adaptive_threshold) const;
  RenderRow measure(const BenchConfiguration& c, uint32_t spp, uint64_t seed);
  // The filter a job with `filter` renders with, as RenderJob chooses it (render_job.h).
  std::string filter_text(const std::optional<std::string>& filter) const;
  // A measured render is timed again while short, and its job's plan line kept for the report.
  Timed run(const RenderOptions& options, bool measured);
  void make_references(const std::optional<std::filesystem::path>& reference_file,
                       const std::filesystem::path& work);

  std::string name_;
  const BenchSettings& settings_;
  const PluginLoader& loader_;
  SceneReport report_;
  Scene scene_;
  std::vector<AveragedReference> references_;
  std::optional<size_t> shot_filter_;
  const AveragedReference* cycles_reference_ = nullptr;
  std::optional<double> cycles_reference_noise_;
  std::vector<double> build_times_;
};

}  // namespace fb
