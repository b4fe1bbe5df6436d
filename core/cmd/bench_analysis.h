// What `filmback bench` concludes from its measurements of one scene: each configuration's
// convergence (least-squares lines of log RMSE against log time and log spp), the error level the
// times are compared at, and the time each configuration needs to reach it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/cmd/bench_metrics.h"
#include "core/cmd/bench_types.h"

namespace fb {

struct ConfigurationFit {
  std::string renderer, configuration;
  ReferenceKind reference = ReferenceKind::kOwn;  // which error of the rows is fitted
  std::vector<const RenderRow*> rows;  // with that error, in the order measured (ascending spp)
  size_t fitted = 0;  // rows whose RMSE is at least kFitAboveReferenceNoise x the reference's
  std::optional<LogLogFit> by_render_s, by_spp;  // of RMSE
  // relMSE against render time: per pixel relative, so it does not favour the darker of two
  // renderers whose images differ in brightness, as RMSE does.
  std::optional<LogLogFit> relmse_by_render_s;
  // What a render costs beside its sampling, the median of total_s - render_s: filmback's import
  // and RenderJob construction, Blender's start, loading and writing. It does not shrink with
  // the sample count, so it is added to the fitted render time rather than fitted with it.
  double fixed_s = 0;
};

// One per configuration that has rows measured against `reference`, in the order of their first
// row.
std::vector<ConfigurationFit> fit_configurations(const SceneReport& scene, ReferenceKind reference);

// The reference the summary compares times on: Cycles' where the scene has it (one reference for
// both renderers), else each configuration's own.
ReferenceKind primary_reference(const SceneReport& scene);

struct TargetError {
  double rmse = 0;
  std::string why;  // how it was chosen
};
// `given` (--target-error), else the largest of the configurations' RMSE at their highest spp
// (against the fits' reference): every configuration reached it within the measured range.
TargetError default_target(const std::vector<ConfigurationFit>& fits, std::optional<double> given);

// Cycles' render the goal names: 256 spp, else Cycles' highest count measured. Its error
// is the same against either reference (Cycles' own is Cycles' reference).
// The first Cycles configuration's (adaptive sampling off, unless --adaptive lists a threshold
// first).
const RenderRow* cycles_reference_render(const std::vector<ConfigurationFit>& fits);
// That render of every Cycles configuration, in order.
std::vector<const RenderRow*> cycles_goal_renders(const std::vector<ConfigurationFit>& fits);
constexpr uint32_t kCyclesGoalSpp = 256;

struct TimeToError {
  std::optional<double> render_s;  // none where the fit is missing or does not fall
  std::optional<double> total_s;   // render_s + fixed_s
  bool extrapolated = false;       // outside the render times the fit was made from
};
// On the fit's reference.
TimeToError time_to_error(const ConfigurationFit& fit, double rmse);
TimeToError time_to_relmse(const ConfigurationFit& fit, double relmse);

}  // namespace fb
