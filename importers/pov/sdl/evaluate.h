// POV-Ray Scene Description Language evaluator: runs a .pov file (directives, macros, loops,
// expressions, includes) and leaves the scene it describes as a pov::Scene. docs/pov.md, "The
// language", lists what is supported.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "importers/pov/pov_animation.h"
#include "importers/pov/pov_scene.h"

namespace fb::pov {

// Bounds that make a hostile or runaway scene fail cleanly with a located error, within a second
// on the development machine. The defaults keep a margin over what Debian's 396 sample scenes
// need (docs/pov.md "The language" has the measured counts).
struct EvaluateLimits {
  uint32_t include_depth = 32;
  uint64_t loop_iterations = 500'000;   // #while/#for iterations, all loops together
  uint32_t macro_depth = 256;           // nested macro calls
  uint64_t tokens = 7'000'000;          // tokens read, macro and loop repeats included
  uint64_t array_elements = 1'000'000;  // array elements allocated, all arrays together
  size_t string_bytes = 1 << 20;        // longest string
  uint64_t objects = 2'000'000;         // objects and triangles created
};

struct EvaluateOptions {
  std::filesystem::path scene_file;
  // Folders searched for #include after the scene's own folder, like POV-Ray's +L.
  std::vector<std::filesystem::path> library_paths;
  // The values of image_width, image_height, clock and frame_number.
  double image_width = 320, image_height = 240, clock = 0, frame_number = 0;
  // What initial_frame, final_frame, initial_clock, final_clock, clock_delta and clock_on read;
  // none: a still, whose clock is all of them.
  std::optional<Animation> animation;
  // Global float identifiers declared before the scene is read (an .ini's Declare=NAME=VALUE).
  std::vector<std::pair<std::string, double>> declarations;
  EvaluateLimits limits;
};

// Throws fb::InputError "file:line:column: what (included from a.pov:3:1)".
pov::Scene evaluate_pov(const EvaluateOptions& options);

}  // namespace fb::pov
