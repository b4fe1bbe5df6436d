// Several seeds per point of `filmback bench` (--seeds), and the names of its configurations: one
// row from the rows of the same configuration and sample count rendered with different seeds, so
// that a firefly one seed draws shows as spread instead of deciding the ranking of samplers
// (issue 17).
#pragma once

#include <string>
#include <vector>

#include "core/cmd/bench_types.h"

namespace fb {

// The median over `rows` (non-empty, one per seed): each error the median seed's by that error's
// RMSE (the lower one of the two middle seeds for an even count), the times and rates the medians,
// with the lowest and highest RMSE as the spread. One row is returned as it is.
RenderRow combine_seeds(const std::vector<RenderRow>& rows);

// "sobol, gaussian" or "sobol, gaussian, adaptive 0.01"; "cycles" or "cycles, adaptive 0.01".
std::string configuration_name(const std::string& base, double adaptive_threshold);

// The median of `values` (the mean of the two middle ones for an even count; 0 for none).
double median(std::vector<double> values);

}  // namespace fb
