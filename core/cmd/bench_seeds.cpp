#include "core/cmd/bench_seeds.h"

#include <algorithm>
#include <cstdio>

namespace fb {
namespace {

// The lower median's position and the lowest and highest value of `rmse`.
struct Ranked {
  size_t median;
  std::pair<double, double> spread;
};
Ranked rank(const std::vector<double>& rmse) {
  std::vector<size_t> order(rmse.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return rmse[a] < rmse[b]; });
  return {order[(order.size() - 1) / 2], {rmse[order.front()], rmse[order.back()]}};
}

}  // namespace

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n == 0 ? 0 : n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

std::string configuration_name(const std::string& base, double adaptive_threshold) {
  if (adaptive_threshold <= 0) return base;
  char text[64];
  std::snprintf(text, sizeof text, ", adaptive %g", adaptive_threshold);
  return base + text;
}

RenderRow combine_seeds(const std::vector<RenderRow>& rows) {
  RenderRow out = rows.front();
  out.seeds = uint32_t(rows.size());
  std::vector<double> own, render_s, total_s, samples_per_s, rays_per_s;
  for (const RenderRow& r : rows) {
    own.push_back(r.own.error.rmse);
    render_s.push_back(r.render_s), total_s.push_back(r.total_s);
    samples_per_s.push_back(r.samples_per_s);
    if (r.rays_per_s) rays_per_s.push_back(*r.rays_per_s);
  }
  const Ranked by_own = rank(own);
  out.own = rows[by_own.median].own;
  out.rmse_spread = by_own.spread;
  out.dropped = rows[by_own.median].dropped;
  out.render_s = median(render_s), out.total_s = median(total_s);
  out.samples_per_s = median(samples_per_s);
  if (rays_per_s.size() == rows.size()) out.rays_per_s = median(rays_per_s);
  if (out.cycles_reference) {
    std::vector<double> against_cycles;
    for (const RenderRow& r : rows)
      against_cycles.push_back(r.cycles_reference ? r.cycles_reference->error.rmse : 0);
    const Ranked by_cycles = rank(against_cycles);
    out.cycles_reference = rows[by_cycles.median].cycles_reference;
    out.cycles_reference_rmse_spread = by_cycles.spread;
  }
  return out;
}

}  // namespace fb
