#include "core/cmd/slurm_commands.h"

#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "core/cmd/bench_process.h"
#include "core/util/error.h"
#include "core/util/program_on_path.h"
#include "core/util/temporary_file.h"

namespace fb {

namespace fs = std::filesystem;

namespace {

constexpr uint64_t kSlurmDefaultMaxArraySize = 1001;

std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

uint64_t slurm_max_array_size() {
  if (!program_on_path("scontrol")) return kSlurmDefaultMaxArraySize;
  TemporaryFile output(fs::temp_directory_path() / "filmback-scontrol.txt");
  const ProgramRun run = run_program({"scontrol", "show", "config"}, output.path());
  std::smatch match;
  const std::string text = file_text(output.path());
  static const std::regex line(R"(MaxArraySize\s*=\s*(\d{1,9}))");
  if (run.exit_status != 0 || !std::regex_search(text, match, line))
    return kSlurmDefaultMaxArraySize;
  return std::max<uint64_t>(1, std::stoull(match[1].str()));
}

void check_sbatch_on_path() {
  if (!program_on_path("sbatch"))
    throw InputError(
        "submit: sbatch is not on PATH (is Slurm's client installed here?); --dry-run writes the "
        "job folder without submitting, and its submit.sh submits it where sbatch is");
}

void run_submit_script(const fs::path& job_dir) {
  const fs::path log = job_dir / "logs" / "submit.log";
  const ProgramRun run = run_program({"bash", (job_dir / "submit.sh").string()}, log);
  std::cout << file_text(log);
  if (run.exit_status != 0)
    throw InputError(describe_failure(run, "submit: " + (job_dir / "submit.sh").string(), log) +
                     "; fix the cause and run it again");
}

}  // namespace fb
