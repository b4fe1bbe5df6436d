#include "core/cmd/bench_filmback.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <utility>

#include "core/accel/render_geometry.h"
#include "core/cmd/bench_seeds.h"
#include "core/image/image_io.h"
#include "core/util/error.h"
#include "importers/import_scene.h"

namespace fb {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Short renders are timed again, up to this many runs or this much time, and the median kept:
// a single run of a few milliseconds says more about the machine's other jobs than the render.
constexpr uint32_t kMostRuns = 5;
constexpr double kRepeatBelow_s = 1.0;

// InputError unless `reference` has the size the scene's renders get.
void check_size(const Image& reference, const fs::path& file, const RenderJob& job) {
  if (reference.width != job.width() || reference.height != job.height())
    throw_input(file.string(), "",
                "the reference is " + std::to_string(reference.width) + "x" +
                    std::to_string(reference.height) + " pixels, the renders " +
                    std::to_string(job.width()) + "x" + std::to_string(job.height()));
}

// Film memory of one render (core/film/film.h): per pixel, each channel's weighted sum and the
// weight in double and the sample count; then the resolved image, a float per channel.
size_t film_bytes(const Image& image) {
  const size_t pixels = size_t(image.width) * image.height, channels = image.channels.size();
  return pixels * ((channels + 1) * sizeof(double) + sizeof(uint32_t) + channels * sizeof(float));
}

}  // namespace

struct FilmbackBench::Timed {
  RenderResult result;  // of the first run (every run gives the same image)
  double build_s = 0, render_s = 0;
  uint32_t runs = 0;
};

FilmbackBench::FilmbackBench(const std::string& name, const fs::path& scene_file,
                             const std::optional<fs::path>& reference_file,
                             const BenchSettings& settings, const PluginLoader& loader,
                             const fs::path& work)
    : name_(name), settings_(settings), loader_(loader) {
  report_.memory.peak_is_the_scene_s = restart_peak_resident_set();
  report_.memory.before = resident_set();
  Diagnostics diagnostics;
  ImportOptions import = settings.import;
  import.resolution = settings.resolution;
  const Clock::time_point imported = Clock::now();
  scene_ = import_scene(scene_file, import, diagnostics);
  report_.import_s = seconds_since(imported);
  diagnostics.print(std::cerr);
  make_references(reference_file, work);
}

RenderOptions FilmbackBench::options(uint32_t spp, SamplerKind sampler,
                                     const std::optional<std::string>& filter, uint64_t seed,
                                     double adaptive_threshold) const {
  RenderOptions o;
  if (settings_.resolution) o.width = settings_.resolution->first;
  if (settings_.resolution) o.height = settings_.resolution->second;
  o.samples_per_pixel = spp;
  o.sampler = sampler;
  o.filter = filter;
  o.seed = seed;
  o.adaptive_threshold = adaptive_threshold;
  o.show_progress = false;
  return o;
}

std::string FilmbackBench::filter_text(const std::optional<std::string>& filter) const {
  return planned_filter_text(filter, scene_.settings);
}

FilmbackBench::Timed FilmbackBench::run(const RenderOptions& options, bool measured) {
  Timed t;
  const Clock::time_point built = Clock::now();
  const RenderJob job(scene_, options, loader_);
  t.build_s = seconds_since(built);
  build_times_.push_back(t.build_s);
  report_.memory.geometry_bytes =
      std::max(report_.memory.geometry_bytes, RenderGeometry::live_bytes());
  if (measured && report_.plan.empty()) report_.plan = job.plan();
  std::vector<double> times;
  double total = 0;
  do {
    const Clock::time_point start = Clock::now();
    RenderResult result = job.run();
    times.push_back(seconds_since(start));
    total += times.back();
    if (times.size() == 1) t.result = std::move(result);
  } while (measured && total < kRepeatBelow_s && times.size() < kMostRuns);
  t.runs = uint32_t(times.size());
  t.render_s = median(times);
  return t;
}

// One per filter: the mean of two renders at half of settings.reference_spp with seeds other than
// the measured renders' (so its noise is independent of theirs), whose difference measures that
// noise; or the image given.
void FilmbackBench::make_references(const std::optional<fs::path>& reference_file,
                                    const fs::path& work) {
  for (size_t f = 0; f < settings_.filters.size(); ++f) {
    const std::optional<std::string>& filter = settings_.filters[f];
    ReferenceNote note{"filmback", filter_text(filter), "", std::nullopt};
    if (reference_file) {
      references_.push_back(
          {colour_channels(read_image(*reference_file), reference_file->string()), {}, {}});
      check_size(
          references_.back().image, *reference_file,
          RenderJob(scene_, options(1, kDefaultSampler, filter, settings_.seed, 0), loader_));
      note.source = reference_file->string();
    } else {
      const uint32_t half = settings_.reference_spp / 2;
      const uint64_t reference_seed = settings_.seed + settings_.seeds;  // after the measured ones
      Image halves[2];
      for (int h = 0; h < 2; ++h) {
        std::cout << "bench: " << name_ << ": reference (" << note.filter << "), half " << h + 1
                  << " of 2 at " << half << " spp" << std::endl;
        Timed t = run(options(half, kDefaultSampler, filter, reference_seed + h, 0), false);
        halves[h] = colour_channels(std::move(t.result.image), name_);
      }
      AveragedReference averaged = average_halves(std::move(halves[0]), std::move(halves[1]));
      note.noise = averaged.noise;
      note.source = "filmback, 2 x " + std::to_string(half) + " spp (" +
                    sampler_name(kDefaultSampler) + ", seeds " + std::to_string(reference_seed) +
                    " and " + std::to_string(reference_seed + 1) + ")";
      write_images(averaged.image, {work / ("reference_filter" + std::to_string(f) + ".exr")}, {});
      references_.push_back(std::move(averaged));
    }
    if (!shot_filter_ && note.filter == shot_filter_text(scene_.settings)) shot_filter_ = f;
    report_.references.push_back(std::move(note));
  }
}

void FilmbackBench::measure_against_cycles(const AveragedReference& cycles,
                                           const ReferenceNote& note) {
  cycles_reference_ = &cycles;
  if (note.noise) cycles_reference_noise_ = note.noise->rmse;
}

void FilmbackBench::render(uint32_t spp) {
  for (const BenchConfiguration& c : settings_.configurations) {
    std::vector<RenderRow> rows;
    for (uint32_t k = 0; k < settings_.seeds; ++k)
      rows.push_back(measure(c, spp, settings_.seed + k));
    report_.rows.push_back(combine_seeds(rows));
  }
}

RenderRow FilmbackBench::measure(const BenchConfiguration& c, uint32_t spp, uint64_t seed) {
  Timed t = run(options(spp, c.sampler, c.filter, seed, c.adaptive_threshold), true);
  report_.memory.film_bytes = film_bytes(t.result.image);
  const Image image = colour_channels(std::move(t.result.image), name_);
  report_.width = image.width, report_.height = image.height;
  RenderRow row;
  row.renderer = "filmback";
  row.sampler = sampler_name(c.sampler);
  row.filter = filter_text(c.filter);
  row.configuration = configuration_name(row.sampler + ", " + row.filter, c.adaptive_threshold);
  row.spp = spp;
  row.runs = t.runs;
  row.render_s = t.render_s;
  row.total_s = report_.import_s + t.build_s + t.render_s;
  row.samples_per_s = double(t.result.stats.samples) / t.render_s;
  row.rays_per_s = double(t.result.stats.rays) / t.render_s;
  row.own.error = image_error(image, references_[c.filter_index].image);
  if (const auto& noise = report_.references[c.filter_index].noise)
    row.own.reference_noise = noise->rmse;
  if (cycles_reference_ && shot_filter_ == c.filter_index &&
      cycles_reference_->image.width == image.width &&
      cycles_reference_->image.height == image.height)
    row.cycles_reference = {image_error(image, cycles_reference_->image), cycles_reference_noise_};
  row.dropped = t.result.stats.dropped_samples;
  char line[320];
  const int n = std::snprintf(
      line, sizeof line, "bench: %s: %s at %u spp, seed %llu: %.3f s (%u runs), RMSE %.4g",
      name_.c_str(), row.configuration.c_str(), spp, static_cast<unsigned long long>(seed),
      row.render_s, row.runs, row.own.error.rmse);
  if (row.cycles_reference && n > 0 && size_t(n) < sizeof line)
    std::snprintf(line + n, sizeof line - n, " (%.4g against Cycles' reference)",
                  row.cycles_reference->error.rmse);
  std::cout << line << std::endl;
  return row;
}

SceneReport FilmbackBench::finish() {
  report_.memory.after = resident_set();
  report_.build_s = median(build_times_);
  return std::move(report_);
}

}  // namespace fb
