// The Blender side of `filmback bench` (docs/cli.md, "bench"): a shot given as a .blend file or a
// bpy script that builds one is prepared once by Blender, which saves it and exports it as glTF
// through filmback's add-on (the file filmback renders); Cycles then renders the saved .blend, one
// Blender process per image, so its time is the whole process's: Blender's start, loading the
// file, Cycles' scene sync and BVH, the render, the EXR written.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/cmd/bench_filmback.h"
#include "core/cmd/bench_types.h"

namespace fb {

// Whether `scene` is a Blender shot (.blend, or .py: a bpy script that builds the shot).
bool is_blender_shot(const std::filesystem::path& scene);

struct BlenderShot {
  std::filesystem::path blend, gltf, work;
  double prepare_s = 0;         // the preparing Blender process, wall time
  std::string cycles_settings;  // one line: what Cycles is set to render with
};

// Builds or opens `source` in Blender, sets the resolution (when given: else the shot's), Cycles
// on the CPU with `threads` (0: all), adaptive sampling (each render sets its own) and denoising
// off, and writes
// work/shot.blend and work/shot.gltf.
BlenderShot prepare_blender_shot(const std::filesystem::path& source,
                                 const std::filesystem::path& work,
                                 const std::optional<std::pair<uint32_t, uint32_t>>& resolution,
                                 unsigned threads);

class CyclesBench {
 public:
  // Cycles' reference: the mean of two renders of half settings.reference_spp with seeds
  // settings.seed + 1 and + 2, like filmback's; and how filmback's reference for the shot's pixel
  // filter agrees with it (compare_references), when a configuration uses that filter.
  CyclesBench(const std::string& name, const BlenderShot& shot, const BenchSettings& settings,
              const FilmbackBench& filmback);

  // Cycles at `spp`: one row per adaptive threshold (0: off), each the median over the seeds.
  void render(uint32_t spp);

  // Cycles' rows, its reference and the comparison, into `report`.
  void add_to(SceneReport& report);

  // The reference both renderers are measured against (FilmbackBench::measure_against_cycles).
  const AveragedReference& reference() const { return reference_; }
  const ReferenceNote& reference_note() const { return reference_note_; }

 private:
  RenderRow measure(uint32_t spp, uint64_t seed, double adaptive_threshold);

  std::string name_;
  const BlenderShot& shot_;
  const BenchSettings& settings_;
  AveragedReference reference_;
  ReferenceNote reference_note_;
  CyclesNote note_;
  std::vector<RenderRow> rows_;
};

}  // namespace fb
