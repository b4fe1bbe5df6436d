// The frames of `filmback submit --frames A-B[:STEP]` and the outputs' `#` patterns, as the tasks'
// command lines need them (docs/distributed.md). Stand-in for frames18's frame_range until it is
// on main: the lead replaces these bodies with calls to it (the same rules: docs/cli.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fb {

// The frame numbers of "A-B[:STEP]" or "N" (A <= B, STEP >= 1, at most 100,000 frames; negative
// frames as "-5--2"): UsageError naming `option` otherwise.
std::vector<int64_t> parse_frame_numbers(const std::string& text, const char* option);

// Whether the file name (the path's last component) holds a run of '#'.
bool has_frame_pattern(const std::string& pattern);

// The last run of '#' in the file name replaced by `frame`, zero-padded to the run's length:
// "shot.####.exr", 12 -> "shot.0012.exr"; -5 -> "shot.-0005.exr" (Blender's BLI_path_frame:
// printf's "%.*d"). Unchanged when the file name holds no '#'.
std::string with_frame_number(const std::string& pattern, int64_t frame);

}  // namespace fb
