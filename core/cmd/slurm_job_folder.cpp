#include "core/cmd/slurm_job_folder.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/cmd/slurm_scripts.h"
#include "core/util/error.h"

namespace fb {

namespace fs = std::filesystem;

namespace {

std::string quoted_list(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) {
    if (!out.empty()) out += ' ';
    out += shell_quoted(w);
  }
  return out;
}

std::vector<std::string> as_strings(const std::vector<fs::path>& paths) {
  std::vector<std::string> out;
  for (const fs::path& p : paths)
    out.push_back(p.string());
  return out;
}

void write_text(const fs::path& file, const std::string& text, bool executable = false) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw_input(file.string(), "", std::string("could not be written: ") + strerror(errno));
  if (executable)
    fs::permissions(file, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
}

fs::path numbered(const fs::path& folder, size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu.sh", index);
  return folder / name;
}

std::string tile_task_file(const TileTask& task) {
  return "name=" + shell_quoted(task.name) + "\npart=" + shell_quoted(task.part.string()) +
         "\ncheckpoint=" + shell_quoted(task.checkpoint.string()) +
         "\nlog=" + shell_quoted(task.log.string()) + "\nrender_args=(" +
         quoted_list(task.render_args) + ")\n";
}

std::string merge_task_file(const MergeTask& task) {
  return "name=" + shell_quoted(task.name) + "\nlog=" + shell_quoted(task.log.string()) +
         "\nparts=(" + quoted_list(as_strings(task.parts)) + ")\noutputs=(" +
         quoted_list(as_strings(task.outputs)) + ")\n";
}

// One sbatch line of submit.sh, its job id into the shell variable `variable`.
std::string sbatch_line(const std::string& variable, const std::vector<std::string>& options,
                        const fs::path& script, const fs::path& job_dir, const ArrayChunk& chunk) {
  std::vector<std::string> words = {"sbatch", "--parsable",
                                    "--array=0-" + std::to_string(chunk.count - 1)};
  words.insert(words.end(), options.begin(), options.end());
  words.insert(words.end(), {script.string(), job_dir.string(), std::to_string(chunk.offset)});
  // --parsable prints "ID" or "ID;CLUSTER".
  return variable + "=$(" + quoted_list(words) + ")\n" + variable + "=${" + variable + "%%;*}\n";
}

}  // namespace

std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (char ch : text)
    out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

std::string submit_script(const SlurmJob& job, const SbatchSettings& settings) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
       "# Submits this filmback job to Slurm (docs/distributed.md); run again to resubmit after "
       "a failure:\n# tasks whose part exists end at once, the others resume from their "
       "checkpoints.\nset -euo pipefail\ncd "
    << shell_quoted(settings.working_dir.string()) << "\n";
  std::vector<std::string> common = {"--chdir=" + settings.working_dir.string(), "--requeue",
                                     "--open-mode=append"};
  common.insert(common.end(), settings.common_options.begin(), settings.common_options.end());
  std::string tile_ids;
  for (size_t i = 0; i < job.tile_arrays.size(); ++i) {
    std::vector<std::string> options = common;
    options.insert(
        options.end(),
        {"--job-name=" + task_name(job.name, std::nullopt, std::nullopt, job.tiles) + ":tiles",
         "--output=" + (job.dir / "logs" / "slurm-%A_%a.out").string()});
    const std::string variable = "tiles_" + std::to_string(i);
    s << sbatch_line(variable, options, job.dir / "tile_task.sh", job.dir, job.tile_arrays[i]);
    s << "echo \"tile array $" << variable << ": tasks " << job.tile_arrays[i].offset << " to "
      << job.tile_arrays[i].offset + job.tile_arrays[i].count - 1 << "\"\n";
    tile_ids += ":$" + variable;
  }
  std::string merge_ids;
  for (size_t i = 0; i < job.merge_arrays.size(); ++i) {
    std::vector<std::string> options = common;
    options.insert(
        options.end(),
        {"--job-name=" + task_name(job.name, std::nullopt, std::nullopt, job.tiles) + ":merge",
         "--output=" + (job.dir / "logs" / "slurm-%A_%a.out").string(),
         "--kill-on-invalid-dep=yes"});
    const std::string variable = "merges_" + std::to_string(i);
    // The dependency holds shell variables: it is spliced in unquoted (job ids are digits).
    std::string line =
        sbatch_line(variable, options, job.dir / "merge_task.sh", job.dir, job.merge_arrays[i]);
    line.insert(line.find("'--array="), "--dependency=afterok" + tile_ids + " ");
    s << line << "echo \"merge array $" << variable << ": frames " << job.merge_arrays[i].offset
      << " to " << job.merge_arrays[i].offset + job.merge_arrays[i].count - 1
      << " of the job, after the tile arrays\"\n";
    merge_ids += " $" + variable;
  }
  s << "echo \"$(date -u +%FT%TZ) tiles" << tile_ids << " merges" << merge_ids << "\" >>"
    << shell_quoted((job.dir / "submitted.txt").string()) << "\n";
  return s.str();
}

void check_job_dir_free(const fs::path& job_dir) {
  std::error_code ec;
  if (fs::exists(job_dir, ec))
    throw_input(job_dir.string(), "",
                "the job folder exists: resubmit its job with its submit.sh, or remove it");
}

void write_job_folder(const SlurmJob& job, const SbatchSettings& settings, const fs::path& plan,
                      const std::string& description) {
  check_job_dir_free(job.dir);
  std::error_code ec;
  const fs::path temporary =
      job.dir.parent_path() / (std::string(".") + job.dir.filename().string() + ".tmp");
  fs::remove_all(temporary, ec);
  if (!fs::create_directories(temporary / "tasks", ec) ||
      !fs::create_directory(temporary / "merges", ec) ||
      !fs::create_directory(temporary / "parts", ec) ||
      !fs::create_directory(temporary / "logs", ec))
    throw_input(job.dir.string(), "", "could not create the job folder: " + ec.message());
  try {
    write_text(temporary / "tile_task.sh", kTileTaskScript, true);
    write_text(temporary / "merge_task.sh", kMergeTaskScript, true);
    write_text(temporary / "job.env",
               "FILMBACK=" + shell_quoted(settings.filmback.string()) +
                   "\nRETRIES=" + std::to_string(settings.retries) +
                   "\nTHREADS_FROM_SLURM=" + (job.threads_from_slurm ? "1" : "0") + "\n");
    for (size_t i = 0; i < job.tile_tasks.size(); ++i)
      write_text(numbered(temporary / "tasks", i), tile_task_file(job.tile_tasks[i]));
    for (size_t i = 0; i < job.merge_tasks.size(); ++i)
      write_text(numbered(temporary / "merges", i), merge_task_file(job.merge_tasks[i]));
    write_text(temporary / "submit.sh", submit_script(job, settings), true);
    write_text(temporary / "job.json", description);
    if (!plan.empty() && !fs::copy_file(plan, temporary / "plan.json", ec))
      throw_input(plan.string(), "", "could not be copied into the job folder: " + ec.message());
  } catch (...) {
    fs::remove_all(temporary, ec);
    throw;
  }
  fs::rename(temporary, job.dir, ec);
  if (ec) {
    fs::remove_all(temporary, ec);
    throw_input(job.dir.string(), "", "could not create the job folder: " + ec.message());
  }
}

}  // namespace fb
