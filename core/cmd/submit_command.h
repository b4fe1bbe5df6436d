// `filmback submit` (docs/distributed.md): a render as a Slurm job, one array task per (frame,
// tile) and a merge per frame that depends on them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace fb {

struct SubmitCommand {
  std::filesystem::path scene;
  std::vector<std::filesystem::path> outputs;  // the final images; with --frames, `#` patterns
  uint32_t tiles = 1;
  std::string frames;  // "A-B[:STEP]"; empty: the scene's frame, no --frame passed
  std::string partition;
  uint32_t retries = 2;            // requeues of a failed task before it may end FAILED
  std::string checkpoint_every;    // passed to every task; empty: no checkpoints
  std::string tile_plan = "auto";  // "auto": `filmback tile-plan` now; "none": equal areas; a file
  bool dry_run = false;
  std::filesystem::path job_dir;   // empty: next to the first output (slurm_job.h)
  std::filesystem::path filmback;  // what the tasks run; empty: this executable
  std::optional<uint32_t> cpus_per_task;
  std::optional<uint64_t> max_array_size;  // none: Slurm's MaxArraySize (scontrol), else 1001
  std::vector<std::string> sbatch_args;    // passed to every sbatch as they are
  std::string name;                        // job names' scene part; empty: the scene's stem
  std::vector<std::string> render_args;    // the rest of the command line, given to every task
};

// Registers `submit` on `app`; the options it does not know are the tasks' render options.
CLI::App* add_submit_command(CLI::App& app, SubmitCommand& command);

int run_submit(SubmitCommand& command);

}  // namespace fb
