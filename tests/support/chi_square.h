// Pearson's chi-square of a histogram against expected counts, cells expecting fewer than 5
// pooled into one (as Mitsuba's chi2 tests do), and the statistic's upper tail at p = 1e-3.
#pragma once

#include <cmath>
#include <vector>

namespace fb::test {

struct ChiSquare {
  double statistic = 0;
  int dof = -1;
  // dof + 3.09 sqrt(2 dof) + 4 (Wilson-Hilferty, rounded up): a correct sampler exceeds it
  // once in a thousand runs at most.
  double limit() const { return dof + 3.1 * std::sqrt(2.0 * dof) + 4; }
};

inline ChiSquare chi_square(const std::vector<double>& observed,
                            const std::vector<double>& expected) {
  ChiSquare r;
  double pooled_o = 0, pooled_e = 0;
  for (size_t c = 0; c < observed.size(); ++c) {
    if (expected[c] < 5) {
      pooled_o += observed[c], pooled_e += expected[c];
      continue;
    }
    r.statistic += (observed[c] - expected[c]) * (observed[c] - expected[c]) / expected[c];
    ++r.dof;
  }
  if (pooled_e >= 5)
    r.statistic += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e, ++r.dof;
  return r;
}

}  // namespace fb::test
