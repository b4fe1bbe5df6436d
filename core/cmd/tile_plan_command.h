// `filmback tile-plan` (docs/cli.md, docs/distributed.md): splits a frame into parts of
// near-equal estimated cost for `render --tile I/N --tile-plan PLAN.json`. The cost per render
// tile comes from a short pre-pass (filmback itself, run with the render's own options at a few
// samples per pixel), from the per-tile seconds the previous frame's parts recorded, or from an
// earlier render's --stats-json report.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fb {

struct TilePlanCommand {
  std::filesystem::path scene;
  uint32_t parts = 0;
  std::filesystem::path output;  // the plan, .json
  // Where the costs come from: the partial films of an earlier frame, or the --stats-json report
  // of an earlier render (its per-tile seconds); neither: a pre-pass.
  std::vector<std::filesystem::path> previous;
  std::filesystem::path report;
  // 4: measured (docs/distributed.md, "Balance"), the parts come out more even than from 1 spp,
  // whose per-tile times are mostly noise, for a pre-pass still a few percent of a production
  // frame's samples.
  uint32_t pre_pass_spp = 4;
  std::vector<std::string> render_arguments;  // as typed after `--`, for the pre-pass
};

// Writes the plan and returns the line that says what it buys (the costliest part over the mean,
// beside the bands `--tile I/N` takes without a plan). `filmback submit --tile-plan auto` calls it
// in its own process: one process start less than running `filmback tile-plan`.
std::string plan_tiles(const TilePlanCommand& command);

// `filmback tile-plan`: plan_tiles, its line printed.
int run_tile_plan(TilePlanCommand& command);

}  // namespace fb
