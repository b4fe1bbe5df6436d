// The files `filmback bench` writes into its report folder (docs/cli.md, "bench"): renders.csv
// (one row per render), fits.csv (each configuration's fitted lines), scenes.csv (per scene: set-up
// times, memory, targets, the bias between renderers) and summary.md, which says what was timed
// and measured and reads the numbers off.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/cmd/bench_types.h"

namespace fb {

struct BenchContext {
  std::string command_line;
  std::string processor;
  std::string started, finished;  // UTC
  std::optional<double> load_before, load_after;
  unsigned threads = 0;
  std::optional<double> target_error;  // --target-error
  std::string plot_interpreter;        // the Python that drew the plots; "" when none did
};

std::string renders_csv(const std::vector<SceneReport>& scenes);
std::string fits_csv(const std::vector<SceneReport>& scenes);
std::string scenes_csv(const std::vector<SceneReport>& scenes, const BenchContext& context);

// `plots` holds each scene's plot file name, or "" where none was drawn.
std::string summary_markdown(const std::vector<SceneReport>& scenes, const BenchContext& context,
                             const std::vector<std::string>& plots);

}  // namespace fb
