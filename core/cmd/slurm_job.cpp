#include "core/cmd/slurm_job.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "core/cmd/frame_range.h"
#include "core/util/error.h"

namespace fb {

namespace fs = std::filesystem;

namespace {

// Render options submit sets for each task itself; typed among the render options they would
// contradict it, so they are refused.
bool sets_option(const std::string& arg, const std::string& option) {
  return arg == option || arg.rfind(option + "=", 0) == 0;
}

void refuse_task_options(const SubmitCommand& c) {
  std::vector<std::string> owned = {"--output",    "--tile",       "--crop",
                                    "--tile-plan", "--checkpoint", "--checkpoint-every",
                                    "--resume",    "--frames",     "--stats-json"};
  if (!c.frames.empty()) owned.push_back("--frame");
  for (const std::string& arg : c.render_args) {
    const bool short_output = arg.rfind("-o", 0) == 0;  // -o FILE or -oFILE
    for (const std::string& option : owned)
      if (short_output || sets_option(arg, option))
        throw UsageError("submit: '" + arg +
                         "' is set by submit for every task (see filmback submit --help: -o, "
                         "--tiles, --frames, --tile-plan, --checkpoint-every)");
  }
}

bool has_option(const std::vector<std::string>& args, const std::string& long_name,
                const std::string& short_name) {
  return std::any_of(args.begin(), args.end(), [&](const std::string& a) {
    return sets_option(a, long_name) || (!short_name.empty() && a == short_name);
  });
}

// Job names and file names keep letters, digits, '.', '_' and '-'.
std::string tame(const std::string& text) {
  std::string out = text;
  for (char& ch : out)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '_' && ch != '-')
      ch = '_';
  return out.empty() ? "render" : out;
}

// `prefix` and `value` with at least `digits` digits: printf's "%s%.*lld".
std::string padded(const char* prefix, int64_t value, int digits) {
  char text[40];
  std::snprintf(text, sizeof text, "%s%.*lld", prefix, digits, static_cast<long long>(value));
  return text;
}

std::string frame_text(int64_t frame) {
  return padded("f", frame, 4);
}

// "f0012.t3" (tile digits as many as the last tile's): the stem of a task's part and log.
std::string task_stem(std::optional<int64_t> frame, uint32_t tile, uint32_t tiles) {
  const std::string tile_text = padded("t", tile, int(std::to_string(tiles - 1).size()));
  return frame ? frame_text(*frame) + "." + tile_text : tile_text;
}

fs::path absolute_path(const fs::path& path) {
  return fs::weakly_canonical(fs::absolute(path));
}

}  // namespace

fs::path default_job_dir(const fs::path& first_output) {
  std::string stem = first_output.stem().string();
  stem.erase(std::remove(stem.begin(), stem.end(), '#'), stem.end());
  while (!stem.empty() && (stem.back() == '.' || stem.back() == '_' || stem.back() == '-'))
    stem.pop_back();
  return first_output.parent_path() / ((stem.empty() ? "render" : stem) + ".filmback-job");
}

std::string task_name(const std::string& name, std::optional<int64_t> frame,
                      std::optional<uint32_t> tile, uint32_t tiles) {
  std::string out = "fb:" + name;
  if (frame) out += ':' + frame_text(*frame);
  if (tile) out += padded(":t", *tile, 1) + "/" + std::to_string(tiles);
  return out;
}

std::vector<ArrayChunk> array_chunks(uint64_t count, uint64_t max_array_size) {
  std::vector<ArrayChunk> chunks;
  for (uint64_t offset = 0; offset < count; offset += max_array_size)
    chunks.push_back({offset, std::min(max_array_size, count - offset)});
  return chunks;
}

SlurmJob plan_slurm_job(const SubmitCommand& c, bool with_plan, uint64_t max_array_size) {
  refuse_task_options(c);
  std::vector<std::optional<int64_t>> frames{std::nullopt};
  if (!c.frames.empty()) {
    frames.clear();
    for (int64_t f : parse_frame_range(c.frames, "--frames").frames())
      frames.emplace_back(f);
    for (const fs::path& out : c.outputs)
      require_frame_pattern(out, "output");
  }
  const uint64_t task_count = uint64_t(frames.size()) * c.tiles;
  if (task_count > kMaxTileTasks)
    throw UsageError("submit: " + std::to_string(frames.size()) + " frames x " +
                     std::to_string(c.tiles) + " tiles = " + std::to_string(task_count) +
                     " tasks, at most " + std::to_string(kMaxTileTasks) + " in one submission");

  SlurmJob job;
  job.dir = absolute_path(c.job_dir.empty() ? default_job_dir(c.outputs.front()) : c.job_dir);
  job.name = tame(c.name.empty() ? c.scene.stem().string() : c.name);
  job.tiles = c.tiles;
  job.threads_from_slurm = !has_option(c.render_args, "--threads", "");
  const std::string scene = absolute_path(c.scene).string();
  const bool quiet = has_option(c.render_args, "--quiet", "-q");
  for (const std::optional<int64_t>& frame : frames) {
    MergeTask merge;
    merge.frame = frame;
    merge.name = task_name(job.name, frame, std::nullopt, c.tiles) + ":merge";
    merge.log = job.dir / "logs" / ((frame ? frame_text(*frame) + "." : "") + "merge.log");
    for (const fs::path& out : c.outputs)
      merge.outputs.push_back(absolute_path(frame ? frame_path(out, *frame) : out));
    for (uint32_t tile = 0; tile < c.tiles; ++tile) {
      TileTask task;
      task.frame = frame;
      task.tile = tile;
      task.name = task_name(job.name, frame, tile, c.tiles);
      const std::string stem = task_stem(frame, tile, c.tiles);
      task.part = job.dir / "parts" / (stem + ".exr");
      task.log = job.dir / "logs" / (stem + ".log");
      std::vector<std::string>& args = task.render_args;
      args.push_back(scene);
      args.insert(args.end(), c.render_args.begin(), c.render_args.end());
      if (frame) args.insert(args.end(), {"--frame", std::to_string(*frame)});
      args.insert(args.end(), {"--tile", std::to_string(tile) + "/" + std::to_string(c.tiles)});
      if (with_plan) args.insert(args.end(), {"--tile-plan", (job.dir / "plan.json").string()});
      args.insert(args.end(), {"-o", task.part.string()});
      if (!c.checkpoint_every.empty()) {
        task.checkpoint = job.dir / "parts" / (stem + ".checkpoint.exr");
        args.insert(args.end(), {"--checkpoint", task.checkpoint.string(), "--checkpoint-every",
                                 c.checkpoint_every});
      }
      if (!quiet) args.push_back("--quiet");
      merge.parts.push_back(task.part);
      job.tile_tasks.push_back(std::move(task));
    }
    job.merge_tasks.push_back(std::move(merge));
  }
  job.tile_arrays = array_chunks(job.tile_tasks.size(), max_array_size);
  job.merge_arrays = array_chunks(job.merge_tasks.size(), max_array_size);
  return job;
}

}  // namespace fb
