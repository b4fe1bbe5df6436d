// The one entry the front end uses: picks the importer by file extension.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"
#include "importers/pov/sdl/evaluate.h"

namespace fb {

// What a scene's own language may ask of the render before the scene exists: POV-Ray scenes read
// image_width/image_height, clock and frame_number, and include files from a library path
// (POV-Ray's +W/+H, +K and +L). glTF files ignore all of it.
struct ImportOptions {
  std::optional<std::pair<uint32_t, uint32_t>> resolution;  // as typed; none: the scene's default
  double clock = 0;
  double frame = 0;
  // An .ini's animation (docs/pov.md ".ini files"): what initial_clock, clock_delta ... read.
  std::optional<pov::Animation> pov_animation;
  std::vector<std::pair<std::string, double>> pov_declarations;  // Declare=NAME=VALUE
  // Folders searched for #include after the scene's own and POV-Ray's standard include folder
  // (when povray-includes is installed), in this order (docs/pov.md "The language").
  std::vector<std::filesystem::path> library_paths;
  // How far a POV-Ray scene's program may run (docs/pov.md "The language": the defaults).
  pov::EvaluateLimits pov_limits;
};

// Whether what the file holds depends on ImportOptions::frame, so that each frame of a sequence
// reads it again: POV-Ray scenes (their program reads frame_number). A glTF file is the same at
// every frame (its animation is evaluated by the render at the frame's time).
bool import_reads_frame(const std::filesystem::path& file);

// Throws UsageError for an unknown extension, InputError for a file that cannot be read.
Scene import_scene(const std::filesystem::path& file, const ImportOptions& options,
                   Diagnostics& diagnostics);

}  // namespace fb
