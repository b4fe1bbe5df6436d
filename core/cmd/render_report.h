// `filmback render --stats-json FILE`: a machine-readable account of one render (docs/cli.md):
// what was asked, what was chosen and why, how long each stage took, what was counted, every
// warning, and how it ended. Written also when the render fails or is interrupted.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/render/render_job.h"

namespace fb {

struct RenderReport {
  std::filesystem::path scene;
  std::optional<int64_t> frame;  // of a frame sequence (--frames)
  std::vector<std::filesystem::path> outputs;
  // "complete", "interrupted" or "error"; in a sequence also "skipped" (its outputs existed)
  std::string status = "error";
  int exit_status = 1;
  std::string error;  // the message, when status is "error"
  std::optional<RenderChoices> choices;
  uint32_t width = 0, height = 0, samples_per_pixel = 0;
  uint64_t seed = 0;
  std::optional<RenderStats> stats;
  uint32_t fewest_samples = 0, most_samples = 0;  // in a pixel
  // Wall seconds of each stage; a stage not reached stays absent.
  std::optional<double> import_s, setup_s, render_s, write_s;
  double total_s = 0;
  std::vector<std::string> warnings;
  std::filesystem::path checkpoint;  // empty: no checkpoints
  bool resumed = false;
  uint32_t checkpoints_written = 0;
  int signal = 0;             // that interrupted the render; 0: none
  double stop_latency_s = 0;  // from the signal to the render loop's return
};

// `filmback render --frames`: the sequence as a whole and one report per frame reached, in order.
struct SequenceReport {
  std::filesystem::path scene;
  std::string frames;  // the range, as FrameRange::text() gives it
  std::string status =
      "error";  // "complete" (every frame rendered or skipped), "interrupted", "error"
  int exit_status = 1;
  std::string error;
  double total_s = 0;
  std::vector<RenderReport> frame_reports;
};

// Throws InputError naming the file if it cannot be written (through a temporary, as images).
void write_render_report(const RenderReport& report, const std::filesystem::path& file);
void write_sequence_report(const SequenceReport& report, const std::filesystem::path& file);

}  // namespace fb
