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
  std::filesystem::path output;                 // the plan, .json
  // Where the costs come from: the partial films of an earlier frame, or the --stats-json report
  // of an earlier render (its per-tile seconds); neither: a pre-pass.
  std::vector<std::filesystem::path> previous;
  std::filesystem::path report;
  uint32_t pre_pass_spp = 1;
  std::vector<std::string> render_arguments;  // as typed after `--`, for the pre-pass
};

int run_tile_plan(TilePlanCommand& command);

// The arguments of the pre-pass render: `render_arguments` without the options the pre-pass sets
// itself or must not inherit (sample count, outputs, report, progress, checkpoints, parts,
// frames), then those set to `spp`, `image` and `report`. Options are dropped in every form
// CLI11 takes: `--spp 4`, `--spp=4`, `-o x`, `-ox`.
std::vector<std::string> pre_pass_arguments(const std::filesystem::path& scene,
                                            const std::vector<std::string>& render_arguments,
                                            uint32_t spp, const std::filesystem::path& image,
                                            const std::filesystem::path& report);

}  // namespace fb
