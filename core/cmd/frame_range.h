// Frame sequences on the command line (docs/cli.md, "Frame sequences"): the range `--frames
// A-B[:STEP]` names, and file-name patterns in which a run of '#' stands for the frame number, as
// Blender writes an animation's frames (`shot.####.exr` -> `shot.0012.exr`). Shared by `render`
// and the front ends of issue 18 that run frames (tile-plan, submit).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fb {

// Whole frame numbers as --frame takes them, and how many frames one range may hold (a typo such
// as 1-1000000 fails at once rather than running for weeks).
constexpr int64_t kMaxFrameNumber = 1'000'000'000;
constexpr int64_t kMaxFramesInRange = 100'000;

// first, first + step, ... up to last (inclusive when step lands on it).
struct FrameRange {
  int64_t first = 0, last = 0, step = 1;

  size_t count() const { return size_t((last - first) / step) + 1; }
  int64_t at(size_t index) const { return first + int64_t(index) * step; }
  std::vector<int64_t> frames() const;
  std::string text() const;  // "1-10:2", "1-10" or "7", as typed in canonical form
};

// "A-B", "A-B:STEP" or "N": integers from -kMaxFrameNumber to kMaxFrameNumber (a leading '-' is
// a negative frame: "-5--1"), A <= B, STEP >= 1, at most kMaxFramesInRange frames. Throws
// UsageError naming `option` and the text, and saying what was expected.
FrameRange parse_frame_range(const std::string& text, const char* option = "--frames");

// Whether the file name (the path's last component) holds a run of '#': a frame pattern. A '#' in
// a folder name is an ordinary character, as for Blender.
bool is_frame_pattern(const std::filesystem::path& pattern);

// The pattern with its frame number: the last run of '#' in the file name replaced by `frame`,
// zero-padded to the run's length, a minus sign before the digits ("####" and -12 -> "-0012"),
// longer numbers written whole; earlier runs stay as they are. This is Blender's BLI_path_frame
// (source/blender/blenlib/intern/path_util.c: the last run of '#' after the last slash, printed as
// "%.*d" with the run's length as precision). A path that is no pattern comes back unchanged.
std::filesystem::path frame_path(const std::filesystem::path& pattern, int64_t frame);

// Throws UsageError "WHAT 'PATTERN': expected a run of '#' in the file name ..." unless `pattern`
// is a frame pattern; `what` names the option ("output", "--checkpoint").
void require_frame_pattern(const std::filesystem::path& pattern, const std::string& what);

}  // namespace fb
