#include "core/cmd/bench_cycles.h"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <utility>

#include "core/cmd/bench_metrics.h"
#include "core/cmd/bench_process.h"
#include "core/cmd/bench_seeds.h"
#include "core/image/image_io.h"
#include "core/util/error.h"
#include "core/util/parse_number.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw_input(file.string(), "", "Blender did not write it");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r'))
    s.pop_back();
  return s;
}

// Runs Blender (-b --factory-startup ARGS); InputError naming its log when it fails.
double run_blender(std::vector<std::string> args, const fs::path& log, const std::string& what) {
  args.insert(args.begin(), {"blender", "-b", "--factory-startup"});
  const ProgramRun run = run_program(args, log);
  if (!run.started || run.exit_status != 0)
    throw InputError(describe_failure(run, "blender (Debian package blender), " + what, log));
  return run.wall_s;
}

struct CyclesRender {
  Image image;           // R, G, B
  double process_s = 0;  // Blender's whole process, wall time
  double render_s = 0;   // bpy.ops.render.render() within it: sync, BVH, sampling
};

// One Blender process rendering shot.blend at `spp` with Cycles' seed `seed` into work/NAME.exr,
// with Cycles' adaptive sampling at `adaptive_threshold` (0: off; its minimum automatic).
CyclesRender render_cycles(const BlenderShot& shot, uint32_t spp, uint64_t seed,
                           double adaptive_threshold, const std::string& name) {
  CyclesRender r;
  const fs::path exr = shot.work / (name + ".exr");
  r.process_s =
      run_blender({shot.blend.string(), "--python-exit-code", "1", "--python",
                   bench_script("cycles_render.py").string(), "--", exr.string(),
                   std::to_string(spp), std::to_string(seed), number_text(adaptive_threshold)},
                  shot.work / (name + ".log"), "Cycles at " + std::to_string(spp) + " spp");
  const fs::path seconds_file = exr.string() + ".render_s";
  const std::string seconds = read_text(seconds_file);
  const std::optional<double> render_s = parse_number(seconds);
  if (!render_s)
    throw_input(seconds_file.string(), "", "expected a number of seconds, found '" + seconds + "'");
  r.render_s = *render_s;
  r.image = colour_channels(read_image(exr), exr.string());
  return r;
}

}  // namespace

bool is_blender_shot(const fs::path& scene) {
  const std::string ext = scene.extension().string();
  return ext == ".blend" || ext == ".py";
}

BlenderShot prepare_blender_shot(const fs::path& source, const fs::path& work,
                                 const std::optional<std::pair<uint32_t, uint32_t>>& resolution,
                                 unsigned threads) {
  BlenderShot shot{work / "shot.blend", work / "shot.gltf", work, 0, {}};
  std::vector<std::string> args;
  if (source.extension() == ".blend") args.push_back(source.string());
  const std::string size =
      resolution ? std::to_string(resolution->first) + "x" + std::to_string(resolution->second)
                 : "shot";
  args.insert(args.end(),
              {"--python-exit-code", "1", "--python", bench_script("blender_prepare.py").string(),
               "--", source.string(), work.string(), size, std::to_string(threads)});
  shot.prepare_s = run_blender(args, work / "prepare.log", "preparing " + source.string());
  shot.cycles_settings = read_text(work / "cycles_settings.txt");
  return shot;
}

CyclesBench::CyclesBench(const std::string& name, const BlenderShot& shot,
                         const BenchSettings& settings, const FilmbackBench& filmback)
    : name_(name), shot_(shot), settings_(settings) {
  note_.settings = shot.cycles_settings;
  const uint32_t half = settings.reference_spp / 2;
  const uint64_t reference_seed = settings.seed + settings.seeds;  // after the measured ones
  Image halves[2];
  for (int h = 0; h < 2; ++h) {
    std::cout << "bench: " << name << ": Cycles reference, half " << h + 1 << " of 2 at " << half
              << " spp" << std::endl;
    halves[h] = render_cycles(shot, half, reference_seed + h, 0,
                              "cycles_reference_" + std::to_string(h + 1))
                    .image;
  }
  reference_ = average_halves(std::move(halves[0]), std::move(halves[1]));
  reference_note_ = {"cycles", "the shot's",
                     "Cycles, 2 x " + std::to_string(half) + " spp (seeds " +
                         std::to_string(reference_seed) + " and " +
                         std::to_string(reference_seed + 1) + ")",
                     reference_.noise};
  const std::optional<size_t> shot_filter = filmback.shot_filter();
  if (!shot_filter) return;
  const AveragedReference& ours = filmback.reference(*shot_filter);
  if (ours.image.width != reference_.image.width || ours.image.height != reference_.image.height)
    return;
  note_.agreement = compare_references(ours, reference_);
  note_.agreement_filter = filmback.reference_note(*shot_filter).filter;
}

void CyclesBench::render(uint32_t spp) {
  for (const double threshold : settings_.adaptive_thresholds) {
    std::vector<RenderRow> rows;
    for (uint32_t k = 0; k < settings_.seeds; ++k)
      rows.push_back(measure(spp, settings_.seed + k, threshold));
    rows_.push_back(combine_seeds(rows));
  }
}

RenderRow CyclesBench::measure(uint32_t spp, uint64_t seed, double adaptive_threshold) {
  const std::string name =
      "cycles_" + std::to_string(spp) + "spp_seed" + std::to_string(seed) +
      (adaptive_threshold > 0 ? "_adaptive" + number_text(adaptive_threshold) : std::string());
  const CyclesRender r = render_cycles(shot_, spp, seed, adaptive_threshold, name);
  RenderRow row;
  row.renderer = "cycles";
  row.configuration = configuration_name("cycles", adaptive_threshold);
  row.sampler = row.filter = "the shot's";
  row.spp = spp;
  row.render_s = r.render_s;
  row.total_s = r.process_s;
  // Pixel samples asked for: with adaptive sampling Cycles takes fewer, and does not say how many.
  row.samples_per_s = double(r.image.width) * r.image.height * spp / r.render_s;
  // Cycles' own reference is Cycles' reference: both measures are the same.
  row.own = {image_error(r.image, reference_.image), reference_.noise.rmse};
  row.cycles_reference = row.own;
  char line[320];
  std::snprintf(line, sizeof line,
                "bench: %s: %s at %u spp, seed %llu: %.3f s render, %.3f s process, RMSE %.4g",
                name_.c_str(), row.configuration.c_str(), spp,
                static_cast<unsigned long long>(seed), row.render_s, row.total_s,
                row.own.error.rmse);
  std::cout << line << std::endl;
  return row;
}

void CyclesBench::add_to(SceneReport& report) {
  report.rows.insert(report.rows.end(), rows_.begin(), rows_.end());
  report.references.push_back(reference_note_);
  report.cycles = note_;
}

}  // namespace fb
