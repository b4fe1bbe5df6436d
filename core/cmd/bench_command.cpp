// `filmback bench` (docs/cli.md, "bench"): checks what was typed, runs every scene through
// filmback (and Cycles), and writes the report folder.
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <set>

#include "core/cmd/bench_cycles.h"
#include "core/cmd/bench_filmback.h"
#include "core/cmd/bench_process.h"
#include "core/cmd/bench_report.h"
#include "core/cmd/commands.h"
#include "core/util/error.h"
#include "core/util/program_on_path.h"
#include "core/util/temporary_file.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// A reference at this many times the highest sample count measured has, for Monte Carlo's
// 1/sqrt(N), a quarter of that render's RMSE (its own noise is measured and reported).
constexpr uint32_t kReferenceSppFactor = 16;
constexpr uint32_t kMostSpp = 1000000;

BenchSettings settings_from(const BenchCommand& c) {
  BenchSettings s;
  s.spp = c.spp;
  std::sort(s.spp.begin(), s.spp.end());
  s.spp.erase(std::unique(s.spp.begin(), s.spp.end()), s.spp.end());
  if (s.spp.size() < 2)
    throw UsageError("--spp: expected at least two different sample counts, to fit a rate");
  s.filters.assign(c.filters.begin(), c.filters.end());
  if (s.filters.empty()) s.filters.push_back(std::nullopt);
  std::vector<SamplerKind> samplers;
  for (const std::string& name : c.samplers) {
    const SamplerKind kind = parse_sampler_kind(name, "--sampler");
    if (std::find(samplers.begin(), samplers.end(), kind) == samplers.end())
      samplers.push_back(kind);
  }
  if (samplers.empty()) samplers.push_back(kDefaultSampler);
  for (const double t : c.adaptive_thresholds)
    if (std::find(s.adaptive_thresholds.begin(), s.adaptive_thresholds.end(), t) ==
        s.adaptive_thresholds.end())
      s.adaptive_thresholds.push_back(t);
  if (s.adaptive_thresholds.empty()) s.adaptive_thresholds.push_back(0);
  for (size_t f = 0; f < s.filters.size(); ++f)
    for (SamplerKind kind : samplers)
      for (const double threshold : s.adaptive_thresholds)
        s.configurations.push_back({kind, s.filters[f], f, threshold});
  if (!c.resolution.empty()) s.resolution = parse_resolution(c.resolution);
  s.reference_spp =
      c.reference_spp.value_or(std::min(kReferenceSppFactor * s.spp.back(), kMostSpp));
  if (s.reference_spp % 2)
    throw UsageError("--reference-spp " + std::to_string(s.reference_spp) +
                     ": expected an even count (the reference is two renders of half of it)");
  s.seed = c.seed;
  s.seeds = c.seeds;
  s.threads = c.threads;
  s.against_cycles = c.against == "cycles";
  s.import = c.import;
  return s;
}

void check_scenes(const BenchCommand& c, const BenchSettings& s) {
  std::set<std::string> names;
  bool any_blender_shot = false;
  for (const fs::path& scene : c.scenes) {
    if (!names.insert(scene.stem().string()).second)
      throw UsageError("scene '" + scene.string() + "': another scene has the name '" +
                       scene.stem().string() + "' (the report names scenes by file name)");
    std::error_code ec;
    if (!fs::is_regular_file(scene, ec)) throw_input(scene.string(), "", "no such file");
    any_blender_shot |= is_blender_shot(scene);
  }
  if (!c.references.empty() && c.references.size() != c.scenes.size())
    throw UsageError("--reference: given " + std::to_string(c.references.size()) + " times for " +
                     std::to_string(c.scenes.size()) + " scenes; expected one per scene, in order");
  if (!c.references.empty() && s.filters.size() > 1)
    throw UsageError(
        "--reference: one image can be the reference of only one pixel filter; "
        "give one --filter");
  if (s.against_cycles && !any_blender_shot)
    throw UsageError(
        "--against cycles: expected a Blender shot (.blend, or a .py that builds one) "
        "among the scenes");
}

// The report folder: created when its parent exists.
void make_output_folder(const fs::path& output) {
  std::error_code ec;
  if (fs::exists(output, ec) && !fs::is_directory(output, ec))
    throw UsageError("-o '" + output.string() + "': is a file, expected a folder");
  const fs::path parent = output.has_parent_path() ? output.parent_path() : ".";
  if (!fs::is_directory(parent, ec))
    throw UsageError("-o '" + output.string() + "': the folder '" + parent.string() +
                     "' does not exist");
  fs::create_directories(output / "work", ec);
  if (ec) throw_input(output.string(), "", "cannot create the report folder: " + ec.message());
}

void write_text(const fs::path& file, const std::string& text) {
  write_atomically(file, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.close();
    return out ? std::string() : std::string("write failed");
  });
}

// Debian's Python, tried first: python3-matplotlib installs into it, while the python3 first on
// PATH may be a version manager's (pyenv) without matplotlib (issue 17).
constexpr const char* kSystemPython = "/usr/bin/python3";

// The interpreters plot.py is tried with, in order: Debian's, then the python3 on PATH when that
// is another file.
std::vector<fs::path> python_candidates() {
  std::vector<fs::path> out;
  if (access(kSystemPython, X_OK) == 0) out.push_back(kSystemPython);
  if (const std::optional<fs::path> on_path = program_on_path("python3")) {
    std::error_code ec;
    if (out.empty() || !fs::equivalent(out.front(), *on_path, ec)) out.push_back(*on_path);
  }
  return out;
}

// Runs plot.py with the first interpreter that has matplotlib; each scene's plot file name, or
// none (with one warning naming the interpreters tried) when it drew none. `interpreter` is the
// one that drew them.
std::vector<std::string> draw_plots(const fs::path& output, const std::vector<SceneReport>& scenes,
                                    std::string& interpreter) {
  const fs::path log = output / "work" / "plot.log";
  const std::vector<fs::path> pythons = python_candidates();
  const char* consequence = ": no plots (the CSV files and summary.md are written)\n";
  std::string without;  // the interpreters that lack matplotlib
  for (const fs::path& python : pythons) {
    const ProgramRun run =
        run_program({python.string(), bench_script("plot.py").string(), output.string()}, log);
    if (run.started && run.exit_status == 0) {
      interpreter = python.string();
      std::cout << "bench: plots drawn by " << interpreter << std::endl;
      std::vector<std::string> plots;
      for (const SceneReport& scene : scenes)
        plots.push_back(scene.name + ".png");
      return plots;
    }
    if (run.exit_status != 3) {
      std::cerr << "filmback: warning: " << describe_failure(run, python.string() + " (plots)", log)
                << consequence;
      return std::vector<std::string>(scenes.size());
    }
    without += (without.empty() ? "" : " nor for ") + python.string();
  }
  if (pythons.empty())
    std::cerr << "filmback: warning: no Python: neither " << kSystemPython
              << " nor a python3 on PATH (Debian packages python3 and python3-matplotlib)"
              << consequence;
  else
    std::cerr << "filmback: warning: matplotlib is not installed for " << without
              << " (Debian package python3-matplotlib, for " << kSystemPython << ")" << consequence;
  return std::vector<std::string>(scenes.size());
}

}  // namespace

int run_bench(BenchCommand& c) {
  const BenchSettings settings = settings_from(c);
  check_scenes(c, settings);
  make_output_folder(c.output);
  // Blender prepares every shot before anything renders: a missing Blender or a broken shot
  // stops the run before its first render.
  std::vector<std::optional<BlenderShot>> shots(c.scenes.size());
  for (size_t i = 0; i < c.scenes.size(); ++i) {
    if (!is_blender_shot(c.scenes[i])) continue;
    const fs::path work = fs::absolute(c.output / "work" / c.scenes[i].stem());
    fs::create_directories(work);
    std::cout << "bench: " << c.scenes[i].stem().string() << ": Blender prepares the shot"
              << std::endl;
    shots[i] = prepare_blender_shot(fs::absolute(c.scenes[i]), work, settings.resolution,
                                    settings.threads);
  }

  BenchContext context;
  context.command_line = c.command_line;
  context.processor = processor_description();
  context.started = utc_now();
  context.load_before = load_average();
  context.threads = c.threads;
  context.target_error = c.target_error;

  std::optional<tbb::global_control> threads;
  if (c.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, c.threads);
  const PluginLoader loader(PluginLoader::default_search_dirs());
  std::vector<SceneReport> reports;
  for (size_t i = 0; i < c.scenes.size(); ++i) {
    const fs::path& scene = c.scenes[i];
    const std::string name = scene.stem().string();
    const fs::path work = c.output / "work" / name;
    fs::create_directories(work);
    const std::optional<fs::path> reference =
        c.references.empty() ? std::nullopt : std::optional(c.references[i]);
    const std::optional<BlenderShot>& shot = shots[i];
    FilmbackBench filmback(name, shot ? shot->gltf : scene, reference, settings, loader, work);
    std::optional<CyclesBench> cycles;
    if (shot && settings.against_cycles) {
      cycles.emplace(name, *shot, settings, filmback);
      filmback.measure_against_cycles(cycles->reference(), cycles->reference_note());
    }
    // Cycles' render at each sample count right after filmback's, so that a change in the
    // machine's load falls on both alike.
    for (uint32_t spp : settings.spp) {
      filmback.render(spp);
      if (cycles) cycles->render(spp);
    }
    reports.push_back(filmback.finish());
    if (shot) reports.back().prepare_s = shot->prepare_s;
    if (cycles) cycles->add_to(reports.back());
    reports.back().name = name;
    reports.back().file = scene;
    // After every scene, so that a long run that fails later keeps what it measured.
    write_text(c.output / "renders.csv", renders_csv(reports));
    write_text(c.output / "fits.csv", fits_csv(reports));
    write_text(c.output / "scenes.csv", scenes_csv(reports, context));
  }
  context.finished = utc_now();
  context.load_after = load_average();

  const std::vector<std::string> plots = draw_plots(c.output, reports, context.plot_interpreter);
  write_text(c.output / "summary.md", summary_markdown(reports, context, plots));
  std::cout << "bench: wrote " << (c.output / "summary.md").string() << std::endl;
  return 0;
}

}  // namespace fb
