// `filmback submit` (docs/distributed.md): plans the tasks (slurm_job.h), makes the tile plan,
// writes the job folder (slurm_job_folder.h) and runs its submit.sh (slurm_commands.h).
#include "core/cmd/submit_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>

#include "core/cmd/bench_process.h"
#include "core/cmd/slurm_commands.h"
#include "core/cmd/slurm_job.h"
#include "core/cmd/slurm_job_folder.h"
#include "core/cmd/tile_plan_command.h"
#include "core/util/error.h"

namespace fb {

namespace fs = std::filesystem;

CLI::App* add_submit_command(CLI::App& app, SubmitCommand& c) {
  CLI::App* cmd = app.add_subcommand(
      "submit",
      "render on a Slurm cluster: an array job of tiles (and frames) and a merge job per frame "
      "that depends on it; options not listed here go to every task's render (docs/"
      "distributed.md)");
  cmd->allow_extras();
  cmd->add_option("scene", c.scene, "scene file, on a file system every node sees")->required();
  cmd->add_option("-o,--output", c.outputs,
                  "final image, .exr, .png or .jpg (repeatable); with --frames a pattern "
                  "shot.####.exr")
      ->required();
  cmd->add_option("--tiles", c.tiles, "parts of each frame, one array task each")
      ->required()
      ->check(CLI::Range(1u, 10000u));
  cmd->add_option("--frames", c.frames, "frames A-B[:STEP] (default: the scene's frame)");
  cmd->add_option("--partition", c.partition, "Slurm partition (default: the cluster's)");
  cmd->add_option("--retries", c.retries,
                  "times a failed task requeues itself, resuming from its checkpoint (default 2)")
      ->check(CLI::Range(0u, 100u));
  cmd->add_option("--checkpoint-every", c.checkpoint_every,
                  "each task saves a checkpoint this often (30s, 5m, ...) that a retry resumes "
                  "from (default: none, a retry starts over)");
  cmd->add_option("--tile-plan", c.tile_plan,
                  "auto: a cost-balanced plan from `filmback tile-plan` (default); none: equal "
                  "areas; or a plan file");
  cmd->add_flag("--dry-run", c.dry_run,
                "write the job folder and print the sbatch commands without running them");
  cmd->add_option("--job-dir", c.job_dir,
                  "the job folder (default: next to the first output, NAME.filmback-job)");
  cmd->add_option("--filmback", c.filmback,
                  "the filmback the tasks run, the same path on every node (default: this one)");
  cmd->add_option("--cpus-per-task", c.cpus_per_task,
                  "Slurm's --cpus-per-task; each task renders with that many threads unless "
                  "--threads is given (default: Slurm's, 1)")
      ->check(CLI::Range(1u, 4096u));
  cmd->add_option("--max-array-size", c.max_array_size,
                  "elements per array (default: Slurm's MaxArraySize, else 1001)")
      ->check(CLI::Range(uint64_t(1), uint64_t(4000001)));
  cmd->add_option("--sbatch-arg", c.sbatch_args,
                  "an option for every sbatch, e.g. --sbatch-arg=--time=2:00:00 (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--name", c.name, "the scene's part of the job names (default: its file name)");
  // What the options above leave are the tasks' render options, in the order typed.
  cmd->callback([cmd, &c] { c.render_args = cmd->remaining(); });
  return cmd;
}

namespace {

fs::path this_executable() {
  const fs::path exe = this_program();
  if (exe.empty()) throw InputError("submit: cannot tell where this filmback is; give --filmback");
  return exe;
}

void check_inputs(const SubmitCommand& c) {
  std::error_code ec;
  if (!fs::is_regular_file(c.scene, ec))
    throw_input(c.scene.string(), "",
                "no such scene file (the scene comes before the render options: filmback submit "
                "SCENE --tiles N -o OUT [render options])");
  for (const fs::path& out : c.outputs) {
    const fs::path folder = out.has_parent_path() ? out.parent_path() : ".";
    if (!fs::is_directory(folder, ec))
      throw UsageError("output '" + out.string() + "': the folder '" + folder.string() +
                       "' does not exist");
  }
  if (c.tile_plan != "auto" && c.tile_plan != "none" && !fs::is_regular_file(c.tile_plan, ec))
    throw UsageError("--tile-plan '" + c.tile_plan + "': expected auto, none or a plan file");
  if (!c.filmback.empty() && !fs::is_regular_file(c.filmback, ec))
    throw_input(c.filmback.string(), "", "--filmback: no such file");
}

// `filmback tile-plan` with the render options, for the first frame, into `plan`: its code, in
// this process (a `filmback tile-plan` process would be one more program start, about a second
// in this sandbox); its pre-pass is one `filmback render` process. Not a Slurm job either: that
// would wait for scheduling passes before the tasks could even be submitted.
void make_auto_plan(const SubmitCommand& c, const SlurmJob& job, const fs::path& plan) {
  TilePlanCommand command;
  command.scene = c.scene;
  command.parts = c.tiles;
  command.output = plan;
  command.render_arguments = c.render_args;
  if (job.tile_tasks.front().frame)
    command.render_arguments.insert(command.render_arguments.end(),
                                    {"--frame", std::to_string(*job.tile_tasks.front().frame)});
  const auto start = std::chrono::steady_clock::now();
  try {
    const std::string line = plan_tiles(command);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "submit: tile plan made in " << seconds << " s: " << line << "\n";
  } catch (const UsageError& e) {
    throw UsageError(std::string("submit: --tile-plan auto: ") + e.what());
  } catch (const InputError& e) {
    throw InputError(std::string("submit: --tile-plan auto: ") + e.what() +
                     " (--tile-plan none splits into equal areas)");
  }
}

std::string job_description(const SubmitCommand& c, const SlurmJob& job,
                            const SbatchSettings& settings, const std::string& plan) {
  using nlohmann::json;
  json frames = json::array();
  for (const MergeTask& m : job.merge_tasks) {
    json parts = json::array(), outputs = json::array();
    for (const fs::path& p : m.parts)
      parts.push_back(p.string());
    for (const fs::path& o : m.outputs)
      outputs.push_back(o.string());
    frames.push_back({{"frame", m.frame ? json(*m.frame) : json(nullptr)},
                      {"parts", parts},
                      {"outputs", outputs}});
  }
  json arrays = json::array();
  for (const ArrayChunk& a : job.tile_arrays)
    arrays.push_back({{"kind", "tiles"}, {"first_task", a.offset}, {"tasks", a.count}});
  for (const ArrayChunk& a : job.merge_arrays)
    arrays.push_back({{"kind", "merge"}, {"first_frame_index", a.offset}, {"tasks", a.count}});
  const json description = {{"format", "filmback-slurm-job"},
                            {"version", 1},
                            {"scene", fs::absolute(c.scene).string()},
                            {"filmback", settings.filmback.string()},
                            {"working_dir", settings.working_dir.string()},
                            {"tiles", c.tiles},
                            {"frames", c.frames},
                            {"task_index", "frame_index * tiles + tile"},
                            {"tile_plan", plan},
                            {"retries", c.retries},
                            {"checkpoint_every", c.checkpoint_every},
                            {"render_options", c.render_args},
                            {"sbatch_options", settings.common_options},
                            {"arrays", arrays},
                            {"per_frame", frames}};
  return description.dump(2) + "\n";
}

}  // namespace

int run_submit(SubmitCommand& c) {
  check_inputs(c);
  if (!c.dry_run) check_sbatch_on_path();
  SbatchSettings settings;
  settings.filmback = fs::absolute(c.filmback.empty() ? this_executable() : c.filmback);
  settings.working_dir = fs::current_path();
  settings.retries = c.retries;
  if (!c.partition.empty()) settings.common_options.push_back("--partition=" + c.partition);
  if (c.cpus_per_task)
    settings.common_options.push_back("--cpus-per-task=" + std::to_string(*c.cpus_per_task));
  settings.common_options.insert(settings.common_options.end(), c.sbatch_args.begin(),
                                 c.sbatch_args.end());
  const bool with_plan = c.tile_plan != "none" && c.tiles > 1;
  const SlurmJob job =
      plan_slurm_job(c, with_plan, c.max_array_size ? *c.max_array_size : slurm_max_array_size());
  check_job_dir_free(job.dir);

  // The plan is made before the folder, so that a failing pre-pass leaves no folder behind.
  fs::path plan;
  const fs::path made_plan =
      job.dir.parent_path() / (std::string(".") + job.dir.filename().string() + ".plan.json");
  if (with_plan && c.tile_plan == "auto") {
    std::cerr << "submit: filmback tile-plan (a low-cost pre-pass of the first frame)\n";
    make_auto_plan(c, job, made_plan);
    plan = made_plan;
  } else if (with_plan) {
    plan = c.tile_plan;
  }
  const std::string description =
      job_description(c, job, settings, with_plan ? c.tile_plan : "none");
  std::error_code ec;
  try {
    write_job_folder(job, settings, plan, description);
  } catch (...) {
    fs::remove(made_plan, ec);
    throw;
  }
  fs::remove(made_plan, ec);
  std::cerr << "submit: job folder " << job.dir.string() << ": " << job.tile_tasks.size()
            << " tile tasks in " << job.tile_arrays.size() << " array(s), "
            << job.merge_tasks.size() << " merge(s)\n";
  if (c.dry_run) {
    std::cout << "# dry run: nothing submitted; to submit, run " << (job.dir / "submit.sh").string()
              << "\n"
              << submit_script(job, settings);
    return 0;
  }
  run_submit_script(job.dir);
  return 0;
}

}  // namespace fb
