// What `filmback bench` measures, scene by scene, and the settings it measures with (docs/cli.md,
// "bench"). Filled by bench_filmback.cpp and bench_cycles.cpp, written by bench_report.cpp.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/cmd/bench_metrics.h"
#include "core/cmd/bench_system.h"
#include "core/render/sampler.h"
#include "importers/import_scene.h"

namespace fb {

struct BenchConfiguration {
  SamplerKind sampler;
  std::optional<std::string> filter;  // none: the scene's (the shot's, else the default)
  size_t filter_index;                // into BenchSettings::filters
  double adaptive_threshold = 0;      // 0: off (docs/sampling.md, "Adaptive sampling")
};

struct BenchSettings {
  std::vector<uint32_t> spp;  // ascending, distinct
  std::vector<std::optional<std::string>> filters;
  std::vector<BenchConfiguration> configurations;  // samplers x filters x adaptive thresholds
  std::vector<double> adaptive_thresholds;         // distinct, in order; 0: off
  std::optional<std::pair<uint32_t, uint32_t>> resolution;
  uint32_t reference_spp = 0;  // both halves together
  uint64_t seed = 0;           // measured renders take seed .. seed + seeds - 1
  uint32_t seeds = 1;          // the reference's halves take seed + seeds and seed + seeds + 1
  unsigned threads = 0;        // 0: all cores
  bool against_cycles = false;
  ImportOptions import;
};

// Renders whose error stays within this factor of their reference's own noise are not fitted:
// there the reference's noise is a tenth or more of the measured MSE.
constexpr double kFitAboveReferenceNoise = 3;

// Which reference a render's error is measured against.
enum class ReferenceKind {
  kOwn,     // the renderer's own: filmback's reference for filmback, Cycles' for Cycles
  kCycles,  // Cycles' reference for both renderers: one reference (issue 14, issue 17)
};

struct MeasuredError {
  ImageError error;
  std::optional<double> reference_noise;  // RMSE of that reference, when measured
};

struct RenderRow {
  std::string renderer;       // "filmback" or "cycles"
  std::string configuration;  // "sobol, gaussian", "cycles"
  std::string sampler, filter;
  uint32_t spp = 0;
  uint32_t runs = 1;    // timed runs (filmback repeats short renders); render_s is their median
  double render_s = 0;  // filmback: RenderJob::run(); Cycles: bpy.ops.render.render()
  double total_s = 0;   // filmback: import + RenderJob construction + run; Cycles: the process
  double samples_per_s = 0;
  std::optional<double> rays_per_s;  // filmback only
  MeasuredError own;                 // against the configuration's own reference
  // Against Cycles' reference: with --against cycles, for Cycles and for the filmback
  // configurations that render with the shot's pixel filter (the one Cycles uses).
  std::optional<MeasuredError> cycles_reference;
  std::optional<uint64_t> dropped;  // non-finite samples; filmback only
  // Several seeds (--seeds): each error above is the median seed's (by that error's RMSE), the
  // times the medians over seeds, and these the lowest and highest RMSE over the seeds.
  uint32_t seeds = 1;
  std::pair<double, double> rmse_spread{0, 0};
  std::optional<std::pair<double, double>> cycles_reference_rmse_spread;

  // The error against `kind`'s reference, or none.
  const MeasuredError* measured(ReferenceKind kind) const {
    return kind == ReferenceKind::kOwn ? &own : cycles_reference ? &*cycles_reference : nullptr;
  }
};

struct ReferenceNote {
  std::string renderer, filter;
  std::string source;  // "filmback, 2 x 2048 spp, seeds 1 and 2", or the file given
  std::optional<ImageError> noise;
};

struct MemoryNote {
  std::optional<ResidentSet> before, after;  // around the scene's import and filmback renders
  bool peak_is_the_scene_s = false;          // false: the peak is the whole process's so far
  size_t geometry_bytes = 0;                 // RenderGeometry::live_bytes() while a job exists
  size_t film_bytes = 0;
};

struct CyclesNote {
  std::string settings;  // blender_prepare.py's line
  // filmback's reference against Cycles' (the same pixel filter); none when no configuration
  // renders with the shot's filter, or the references differ in size.
  std::optional<ReferenceAgreement> agreement;
  std::string agreement_filter;
};

struct SceneReport {
  std::string name;
  std::filesystem::path file;  // as given
  uint32_t width = 0, height = 0;
  std::string plan;                 // filmback's plan line for the first configuration
  std::optional<double> prepare_s;  // a Blender shot: Blender building, saving, exporting it
  double import_s = 0;
  double build_s = 0;  // RenderJob construction, median over the scene's jobs
  std::vector<ReferenceNote> references;
  MemoryNote memory;
  std::optional<CyclesNote> cycles;
  std::vector<RenderRow> rows;
};

}  // namespace fb
