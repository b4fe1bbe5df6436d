// The Slurm commands `filmback submit` runs itself: scontrol for MaxArraySize, and the job
// folder's submit.sh (sbatch) to submit (docs/distributed.md).
#pragma once

#include <cstdint>
#include <filesystem>

namespace fb {

// Slurm's MaxArraySize (`scontrol show config`): an array's indices must stay below it. Slurm's
// default, 1001, when scontrol is not there or does not say.
uint64_t slurm_max_array_size();

// InputError when sbatch is not on PATH, suggesting --dry-run.
void check_sbatch_on_path();

// Runs `job_dir`/submit.sh, its output (the job ids) to stdout and to logs/submit.log. InputError
// when it fails.
void run_submit_script(const std::filesystem::path& job_dir);

}  // namespace fb
