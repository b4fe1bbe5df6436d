// What `filmback submit` sends to Slurm, as data (docs/distributed.md): one tile task per (frame,
// tile) at index frame_index * tiles + tile, one merge task per frame, and the arrays they are
// submitted in (at most MaxArraySize elements each, indices 0..count-1 plus an offset).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/cmd/submit_command.h"

namespace fb {

// A part of one frame: `filmback render ARGS` writes `part` (and `checkpoint` while it runs).
struct TileTask {
  std::optional<int64_t> frame;  // none: the scene's frame
  uint32_t tile = 0;
  std::string name;  // the job name squeue shows, e.g. "fb:shot:f0012:t3/8"
  std::filesystem::path part, checkpoint, log;  // checkpoint empty: none
  std::vector<std::string> render_args;         // after `filmback render`
};

// The merge of one frame's parts into its outputs.
struct MergeTask {
  std::optional<int64_t> frame;
  std::string name;
  std::vector<std::filesystem::path> parts, outputs;
  std::filesystem::path log;
};

// Array elements [offset, offset + count) of the task list, submitted as --array=0-(count-1).
struct ArrayChunk {
  uint64_t offset = 0, count = 0;
};

struct SlurmJob {
  std::filesystem::path dir;  // the job folder: scripts, tasks/, parts/, logs/
  std::string name;           // the scene part of job names
  uint32_t tiles = 1;
  // Whether tasks get --threads from Slurm's --cpus-per-task (the render options name none).
  bool threads_from_slurm = true;
  std::vector<TileTask> tile_tasks;
  std::vector<MergeTask> merge_tasks;
  std::vector<ArrayChunk> tile_arrays, merge_arrays;
};

// At most this many tile tasks in one submission (each has a small file in tasks/).
constexpr uint64_t kMaxTileTasks = 100000;

// The job folder next to the first output: "renders/shot.####.exr" -> "renders/shot.filmback-job"
// (the extension, `#` runs and the separators before them dropped).
std::filesystem::path default_job_dir(const std::filesystem::path& first_output);

// "fb:NAME:fFRAME:tTILE/TILES", the parts left out that are not there (no frame: the scene's).
std::string task_name(const std::string& name, std::optional<int64_t> frame,
                      std::optional<uint32_t> tile, uint32_t tiles);

// Splits `count` tasks into arrays of at most `max_array_size` elements.
std::vector<ArrayChunk> array_chunks(uint64_t count, uint64_t max_array_size);

// The tasks of `command` (paths absolute; outputs with their frame substituted), the render
// options after the scene as typed; `with_plan`: the tasks read the job folder's plan.json.
// UsageError on a command line submit cannot turn into tasks.
SlurmJob plan_slurm_job(const SubmitCommand& command, bool with_plan, uint64_t max_array_size);

}  // namespace fb
