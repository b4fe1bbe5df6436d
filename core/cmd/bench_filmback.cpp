#include "core/cmd/bench_filmback.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include "core/accel/render_geometry.h"
#include "core/image/image_io.h"
#include "core/render/render_job.h"
#include "core/util/error.h"

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

struct Timed {
  RenderResult result;  // of the first run (every run gives the same image)
  double build_s = 0, render_s = 0;
  uint32_t runs = 0;
};

class SceneBench {
 public:
  SceneBench(const Scene& scene, const BenchSettings& settings, const PluginLoader& loader)
      : scene_(scene), settings_(settings), loader_(loader) {}

  RenderOptions options(uint32_t spp, SamplerKind sampler, const std::optional<std::string>& filter,
                        uint64_t seed) const {
    RenderOptions o;
    if (settings_.resolution) o.width = settings_.resolution->first;
    if (settings_.resolution) o.height = settings_.resolution->second;
    o.samples_per_pixel = spp;
    o.sampler = sampler;
    o.filter = filter;
    o.seed = seed;
    o.show_progress = false;
    return o;
  }

  // The filter a job with `filter` renders with, as RenderJob chooses it (render_job.h).
  std::string filter_text(const std::optional<std::string>& filter) const {
    return filter.value_or(scene_.settings.filter.value_or(kDefaultFilter));
  }

  // A measured render is timed again while short, and its job's plan line is kept for the report.
  Timed render(const RenderOptions& options, bool measured) {
    Timed t;
    const Clock::time_point built = Clock::now();
    const RenderJob job(scene_, options, loader_);
    t.build_s = seconds_since(built);
    build_times_.push_back(t.build_s);
    geometry_bytes_ = std::max(geometry_bytes_, RenderGeometry::live_bytes());
    if (measured && plan_.empty()) plan_ = job.plan();
    std::vector<double> times;
    double total = 0;
    do {
      const Clock::time_point start = Clock::now();
      RenderResult result = job.run();
      times.push_back(seconds_since(start));
      total += times.back();
      if (times.size() == 1) t.result = std::move(result);
    } while (measured && total < kRepeatBelow_s && times.size() < kMostRuns);
    std::sort(times.begin(), times.end());
    t.runs = uint32_t(times.size());
    t.render_s = times.size() % 2 ? times[times.size() / 2]
                                  : 0.5 * (times[times.size() / 2 - 1] + times[times.size() / 2]);
    return t;
  }

  double median_build_s() const {
    std::vector<double> b = build_times_;
    std::sort(b.begin(), b.end());
    return b.empty() ? 0 : b[b.size() / 2];
  }
  size_t geometry_bytes() const { return geometry_bytes_; }
  const std::string& plan() const { return plan_; }

 private:
  const Scene& scene_;
  const BenchSettings& settings_;
  const PluginLoader& loader_;
  std::vector<double> build_times_;
  size_t geometry_bytes_ = 0;
  std::string plan_;
};

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

FilmbackBench bench_filmback(const std::string& name, const fs::path& scene_file,
                             const std::optional<fs::path>& reference_file,
                             const BenchSettings& settings, const PluginLoader& loader,
                             const fs::path& work) {
  FilmbackBench out;
  SceneReport& report = out.report;
  report.memory.peak_is_the_scene_s = restart_peak_resident_set();
  report.memory.before = resident_set();

  Diagnostics diagnostics;
  ImportOptions import = settings.import;
  import.resolution = settings.resolution;
  const Clock::time_point imported = Clock::now();
  const Scene scene = import_scene(scene_file, import, diagnostics);
  report.import_s = seconds_since(imported);
  diagnostics.print(std::cerr);
  SceneBench bench(scene, settings, loader);

  // References, one per filter: the same scene at settings.reference_spp, as the mean of two
  // renders with seeds other than the measured renders' (so its noise is independent of theirs),
  // whose difference measures that noise.
  for (size_t f = 0; f < settings.filters.size(); ++f) {
    const std::optional<std::string>& filter = settings.filters[f];
    ReferenceNote note{"filmback", bench.filter_text(filter), "", std::nullopt};
    if (reference_file) {
      out.references.push_back(
          colour_channels(read_image(*reference_file), reference_file->string()));
      check_size(
          out.references.back(), *reference_file,
          RenderJob(scene, bench.options(1, kDefaultSampler, filter, settings.seed), loader));
      note.source = reference_file->string();
    } else {
      const uint32_t half = settings.reference_spp / 2;
      Image halves[2];
      for (int h = 0; h < 2; ++h) {
        std::cout << "bench: " << name << ": reference (" << note.filter << "), half " << h + 1
                  << " of 2 at " << half << " spp" << std::endl;
        const Timed t = bench.render(
            bench.options(half, kDefaultSampler, filter, settings.seed + 1 + h), false);
        halves[h] = colour_channels(t.result.image, name);
      }
      AveragedReference averaged = average_halves(halves[0], halves[1]);
      note.noise = averaged.noise;
      note.source = "filmback, 2 x " + std::to_string(half) + " spp (" +
                    sampler_name(kDefaultSampler) + ", seeds " + std::to_string(settings.seed + 1) +
                    " and " + std::to_string(settings.seed + 2) + ")";
      write_images(averaged.image, {work / ("reference_filter" + std::to_string(f) + ".exr")}, {});
      out.references.push_back(std::move(averaged.image));
    }
    if (!out.shot_filter && scene.settings.filter && note.filter == *scene.settings.filter)
      out.shot_filter = f;
    report.references.push_back(std::move(note));
  }

  // Sample counts in the outer loop: every configuration takes its turn at each count, so a
  // change in the machine's load falls on all of them alike.
  for (uint32_t spp : settings.spp)
    for (const BenchConfiguration& c : settings.configurations) {
      const Timed t = bench.render(bench.options(spp, c.sampler, c.filter, settings.seed), true);
      const Image image = colour_channels(t.result.image, name);
      report.width = image.width, report.height = image.height;
      report.memory.film_bytes = film_bytes(t.result.image);
      RenderRow row;
      row.renderer = "filmback";
      row.sampler = sampler_name(c.sampler);
      row.filter = bench.filter_text(c.filter);
      row.configuration = row.sampler + ", " + row.filter;
      row.spp = spp;
      row.runs = t.runs;
      row.render_s = t.render_s;
      row.total_s = report.import_s + t.build_s + t.render_s;
      row.samples_per_s = double(t.result.stats.samples) / t.render_s;
      row.rays_per_s = double(t.result.stats.rays) / t.render_s;
      row.error = image_error(image, out.references[c.filter_index]);
      row.dropped = t.result.stats.dropped_samples;
      if (const auto& noise = report.references[c.filter_index].noise)
        row.reference_noise = noise->rmse;
      char line[256];
      std::snprintf(line, sizeof line, "bench: %s: %s at %u spp: %.3f s (%u runs), RMSE %.4g",
                    name.c_str(), row.configuration.c_str(), spp, row.render_s, row.runs,
                    row.error.rmse);
      std::cout << line << std::endl;
      report.rows.push_back(std::move(row));
    }
  report.memory.after = resident_set();
  report.memory.geometry_bytes = bench.geometry_bytes();
  report.build_s = bench.median_build_s();
  report.plan = bench.plan();
  return out;
}

}  // namespace fb
