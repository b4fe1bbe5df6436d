// The command line of the pre-pass render that `filmback tile-plan` runs to measure a frame's cost
// per tile (core/cmd/tile_plan_command.h): the render's own options, less those the pre-pass sets
// itself or must not inherit.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fb {

// `render SCENE`, then `render_arguments` without the sample count, outputs, report, progress,
// checkpoints, parts and frame range (a range becomes `--frame` of its first frame: the parts of
// every frame share the plan), then those set to `spp`, `image` and `report`. Options are dropped
// in every form CLI11 takes: `--spp 4`, `--spp=4`, `-o x`, `-ox`.
std::vector<std::string> pre_pass_arguments(const std::filesystem::path& scene,
                                            const std::vector<std::string>& render_arguments,
                                            uint32_t spp, const std::filesystem::path& image,
                                            const std::filesystem::path& report);

}  // namespace fb
