#include "core/cmd/bench_analysis.h"

#include <algorithm>

namespace fb {

std::vector<ConfigurationFit> fit_configurations(const SceneReport& scene,
                                                 ReferenceKind reference) {
  std::vector<ConfigurationFit> fits;
  for (const RenderRow& row : scene.rows) {
    if (!row.measured(reference)) continue;
    auto it = std::find_if(fits.begin(), fits.end(), [&](const ConfigurationFit& f) {
      return f.renderer == row.renderer && f.configuration == row.configuration;
    });
    if (it == fits.end()) {
      ConfigurationFit fit;
      fit.renderer = row.renderer;
      fit.configuration = row.configuration;
      fit.reference = reference;
      it = fits.insert(fits.end(), std::move(fit));
    }
    it->rows.push_back(&row);
  }
  for (ConfigurationFit& fit : fits) {
    std::vector<double> render_s, spp, rmse, relmse, fixed_s;
    for (const RenderRow* row : fit.rows) {
      fixed_s.push_back(row->total_s - row->render_s);
      const MeasuredError& m = *row->measured(reference);
      if (m.reference_noise && m.error.rmse < kFitAboveReferenceNoise * *m.reference_noise)
        continue;
      render_s.push_back(row->render_s);
      spp.push_back(row->spp);
      rmse.push_back(m.error.rmse);
      relmse.push_back(m.error.relmse);
    }
    fit.fitted = rmse.size();
    fit.by_render_s = fit_log_log(render_s, rmse);
    fit.by_spp = fit_log_log(spp, rmse);
    fit.relmse_by_render_s = fit_log_log(render_s, relmse);
    std::sort(fixed_s.begin(), fixed_s.end());
    fit.fixed_s = fixed_s[fixed_s.size() / 2];
  }
  return fits;
}

ReferenceKind primary_reference(const SceneReport& scene) {
  for (const RenderRow& row : scene.rows)
    if (row.cycles_reference) return ReferenceKind::kCycles;
  return ReferenceKind::kOwn;
}

TargetError default_target(const std::vector<ConfigurationFit>& fits, std::optional<double> given) {
  if (given) return {*given, "given with --target-error"};
  TargetError target{0, ""};
  for (const ConfigurationFit& fit : fits) {
    const RenderRow& last = *fit.rows.back();
    const double rmse = last.measured(fit.reference)->error.rmse;
    if (rmse > target.rmse)
      target = {rmse, "the largest RMSE any configuration has at its highest spp (" +
                          fit.configuration + " at " + std::to_string(last.spp) +
                          " spp), so every configuration reaches it within the "
                          "measured range"};
  }
  return target;
}

std::vector<const RenderRow*> cycles_goal_renders(const std::vector<ConfigurationFit>& fits) {
  std::vector<const RenderRow*> out;
  for (const ConfigurationFit& fit : fits) {
    if (fit.renderer != "cycles") continue;
    const auto goal = std::find_if(fit.rows.begin(), fit.rows.end(),
                                   [](const RenderRow* row) { return row->spp == kCyclesGoalSpp; });
    out.push_back(goal != fit.rows.end() ? *goal : fit.rows.back());
  }
  return out;
}

const RenderRow* cycles_reference_render(const std::vector<ConfigurationFit>& fits) {
  const std::vector<const RenderRow*> rows = cycles_goal_renders(fits);
  return rows.empty() ? nullptr : rows.front();
}

namespace {

TimeToError time_on(const std::optional<LogLogFit>& line, double fixed_s, double error) {
  TimeToError t;
  if (line) t.render_s = line->x_at(error);
  if (t.render_s) {
    t.total_s = *t.render_s + fixed_s;
    t.extrapolated = line->extrapolates(*t.render_s);
  }
  return t;
}

}  // namespace

TimeToError time_to_error(const ConfigurationFit& fit, double rmse) {
  return time_on(fit.by_render_s, fit.fixed_s, rmse);
}

TimeToError time_to_relmse(const ConfigurationFit& fit, double relmse) {
  return time_on(fit.relmse_by_render_s, fit.fixed_s, relmse);
}

}  // namespace fb
