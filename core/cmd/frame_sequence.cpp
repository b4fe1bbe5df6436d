#include "core/cmd/frame_sequence.h"

#include <iostream>

#include "core/image/image_io.h"
#include "core/util/error.h"

namespace fb {
namespace {

// "a.0012.exr exists", "a.0012.exr, a.0012.png exist"
std::string existing_outputs(const std::vector<std::filesystem::path>& outputs) {
  std::string text;
  for (const std::filesystem::path& output : outputs)
    text += (text.empty() ? "" : ", ") + output.string();
  return text + (outputs.size() == 1 ? " exists" : " exist");
}

}  // namespace

FrameFiles frame_files(int64_t frame, const std::vector<std::filesystem::path>& output_patterns,
                       const std::filesystem::path& checkpoint_pattern) {
  FrameFiles files{frame, {}, {}};
  for (const std::filesystem::path& pattern : output_patterns)
    files.outputs.push_back(frame_path(pattern, frame));
  if (!checkpoint_pattern.empty()) files.checkpoint = frame_path(checkpoint_pattern, frame);
  return files;
}

bool frame_done(const FrameFiles& files) {
  std::error_code ec;
  if (!files.checkpoint.empty() && std::filesystem::exists(files.checkpoint, ec)) return false;
  for (const std::filesystem::path& output : files.outputs)
    if (!is_finished_image(output)) return false;
  return true;
}

int run_frame_sequence(const FrameSequence& sequence, const InterruptGuard& interrupts,
                       const FrameRenderer& render_frame, SequenceReport& report) {
  report.frames = sequence.range.text();
  for (size_t i = 0; i < sequence.range.count(); ++i) {
    // A signal after the last frame's render loop (while its files were written) ends the
    // sequence here; one while the next frame's scene is read stops that frame before a sample.
    if (interrupts.requested()) return 128 + interrupts.signal_number();
    const FrameFiles files =
        frame_files(sequence.range.at(i), sequence.output_patterns, sequence.checkpoint_pattern);
    RenderReport& frame = report.frame_reports.emplace_back();
    frame.scene = report.scene;
    frame.frame = files.frame;
    frame.outputs = files.outputs;
    if (!sequence.overwrite && frame_done(files)) {
      std::cerr << "filmback: frame " << files.frame << ": skipped, "
                << existing_outputs(files.outputs) << " (--overwrite renders it again)\n";
      frame.status = "skipped", frame.exit_status = 0;
      continue;
    }
    int status = 1;
    try {
      status = render_frame(files, frame);
    } catch (const std::exception& e) {
      frame.error = e.what();
      frame.exit_status = dynamic_cast<const UsageError*>(&e) ? 2 : 1;
      std::cerr << "filmback: frame " << files.frame << " of " << report.frames
                << " failed; the frames before it are done\n";
      throw;
    }
    if (status != 0) return status;
  }
  return 0;
}

}  // namespace fb
