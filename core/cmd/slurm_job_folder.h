// The job folder of `filmback submit` (docs/distributed.md): the task scripts, one small bash file
// per task (tasks/, merges/), job.env, job.json (what was submitted) and submit.sh, the sbatch
// commands that submit it, and again after a failure (tasks whose part exists end at once).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/cmd/slurm_job.h"

namespace fb {

// `text` as one bash word: single-quoted, a quote inside as '\''.
std::string shell_quoted(const std::string& text);

// How the job's arrays are submitted: what every sbatch gets besides the array and its script.
struct SbatchSettings {
  std::filesystem::path filmback;           // the executable the tasks run (absolute)
  std::filesystem::path working_dir;        // the tasks' working folder: where submit ran
  std::vector<std::string> common_options;  // --partition, --cpus-per-task, the --sbatch-arg's
  uint32_t retries = 2;
};

// The text of submit.sh: the tile arrays, then the merge arrays with
// `--dependency=afterok:TILE_ARRAYS --kill-on-invalid-dep=yes`, printing the job ids.
std::string submit_script(const SlurmJob& job, const SbatchSettings& settings);

// InputError naming `job_dir` when it exists (a job folder is never reused: see submit.sh).
void check_job_dir_free(const std::filesystem::path& job_dir);

// Writes the whole folder `job.dir` (parts/ and logs/ empty): into a temporary sibling, renamed
// into place, so that a failure leaves none. `plan`: copied in as plan.json when not empty.
// `description`: job.json's text. InputError naming the folder when it exists or cannot be made.
void write_job_folder(const SlurmJob& job, const SbatchSettings& settings,
                      const std::filesystem::path& plan, const std::string& description);

}  // namespace fb
