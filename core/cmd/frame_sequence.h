// `filmback render --frames A-B[:STEP]` (docs/cli.md, "Frame sequences"): the frames in order,
// each written by the render as one frame is; a frame whose outputs are all there is skipped; a
// signal ends the sequence once the frame it stopped is saved.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "core/cmd/frame_range.h"
#include "core/cmd/interrupts.h"
#include "core/cmd/render_report.h"

namespace fb {

// One frame's files: the patterns with its number.
struct FrameFiles {
  int64_t frame = 0;
  std::vector<std::filesystem::path> outputs;
  std::filesystem::path checkpoint;  // empty: no checkpoints
};

FrameFiles frame_files(int64_t frame, const std::vector<std::filesystem::path>& output_patterns,
                       const std::filesystem::path& checkpoint_pattern);

// A frame is done when each output is a finished image (core/image/image_io.h,
// is_finished_image) and it has no checkpoint (which a finished render removes).
bool frame_done(const FrameFiles& files);

// Renders one frame into its files and fills its report; returns the exit status (0, or
// 128 + the signal when interrupted). Throws as the render does.
using FrameRenderer = std::function<int(const FrameFiles& files, RenderReport& report)>;

struct FrameSequence {
  FrameRange range;
  std::vector<std::filesystem::path> output_patterns;
  std::filesystem::path checkpoint_pattern;  // empty: no checkpoints
  bool overwrite = false;                    // render frames that are done again
};

// Runs the frames in order, a report for each frame reached into `report`; returns 0 when every
// frame was rendered or skipped, else the interrupted frame's status (no later frame starts; nor
// does one after a signal that came between frames). A frame's error stops the sequence: its
// report says so, a line on stderr names the frame, and the error is thrown on.
int run_frame_sequence(const FrameSequence& sequence, const InterruptGuard& interrupts,
                       const FrameRenderer& render_frame, SequenceReport& report);

}  // namespace fb
