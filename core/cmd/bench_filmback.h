// filmback's side of `filmback bench`: one scene imported once, its references, and every
// configuration at every sample count, each render through its own RenderJob.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/cmd/bench_types.h"
#include "core/image/image.h"
#include "core/plugin/loader.h"

namespace fb {

struct FilmbackBench {
  SceneReport report;
  std::vector<Image> references;  // R, G, B per BenchSettings::filters entry
  // The first filter that is the scene's own pixel filter (the one Cycles renders a Blender shot
  // with), if any.
  std::optional<size_t> shot_filter;
};

// `scene_file` is what filmback reads (a Blender shot's export); `reference_file`, when given,
// replaces filmback's own reference; work files (the references as EXR) go to `work`.
FilmbackBench bench_filmback(const std::string& name, const std::filesystem::path& scene_file,
                             const std::optional<std::filesystem::path>& reference_file,
                             const BenchSettings& settings, const PluginLoader& loader,
                             const std::filesystem::path& work);

}  // namespace fb
