// Primary-ray throughput: filmback's whole render (RenderJob::run with the `aov` integrator, one
// camera ray per sample) against raw Embree rtcIntersect1 on the same scene, the same rays and
// the same TBB thread count, in one run. Before timing, both sides trace once and must agree:
// the same number of rays and hits, and filmback's depth AOV equal to Embree's hit distance
// times cos(theta) per pixel. The ratio of the medians is printed last (docs/benchmarks.md).
//
//   primary_rays_bench [--res=PX] [--segments=N] [--threads=T] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/plugin/loader.h"
#include "core/render/render_job.h"
#include "core/util/error.h"
#include "tests/bench/bench_flags.h"
#include "tests/bench/bench_scenes.h"
#include "tests/bench/embree_baseline.h"

namespace fb::bench {
namespace {

struct Settings {
  uint32_t resolution_px = 1024;  // square image
  uint32_t segments = 1024;       // sphere: segments^2 triangles; terrain: about as many
  uint32_t threads = 2;
  uint32_t samples_per_pixel = 8;  // the second set of cases; the first is always 1 spp
};

struct Case {
  std::string name;
  uint32_t samples_per_pixel;
  Scene scene;
  std::unique_ptr<RenderJob> job;
  std::unique_ptr<EmbreeBaseline> baseline;
};

std::unique_ptr<Case> make_case(std::string name, uint32_t samples_per_pixel, Scene scene,
                                const Settings& settings, const PluginLoader& loader) {
  auto c = std::make_unique<Case>(
      Case{std::move(name), samples_per_pixel, std::move(scene), nullptr, nullptr});
  RenderOptions options;
  options.width = options.height = settings.resolution_px;
  options.samples_per_pixel = samples_per_pixel;
  options.integrator = "aov";
  options.filter = "box";
  options.show_progress = false;
  c->job = std::make_unique<RenderJob>(c->scene, options, loader);
  c->baseline = std::make_unique<EmbreeBaseline>(c->scene, c->job->camera(), settings.resolution_px,
                                                 settings.resolution_px);
  return c;
}

// Depth from the barycentric hit point (filmback) and from t cos(theta) (here) round differently.
// Measured at 1024x1024: 4e-7 on the sphere, 5e-6 at grazing incidence on the terrain (8e-6 with
// RTC_SCENE_FLAG_ROBUST). Moving every ray by 0.01 px gives 5e-5 on the sphere and 0.3 on the
// terrain, so 2e-5 tells rounding from tracing other rays.
constexpr double kDepthTolerance = 2e-5;

// Traces both sides once and prints how well they agree; false when they traced different rays.
bool check_agreement(const Case& c) {
  const RenderResult render = c.job->run();
  std::vector<float> embree_depth;
  const uint64_t embree_hits = c.baseline->trace(embree_depth, 1);
  const auto& channels = render.image.channels;
  const size_t z = size_t(std::find(channels.begin(), channels.end(), "Z") - channels.begin());
  uint64_t filmback_hits = 0, disagreements = 0;
  double max_error = 0;
  for (uint32_t y = 0; y < render.image.height; ++y)
    for (uint32_t x = 0; x < render.image.width; ++x) {
      const float ours = render.image.at(x, y, z);
      const float theirs = embree_depth[size_t(y) * render.image.width + x];
      const bool ours_hit = ours != EmbreeBaseline::kMissDepth;
      filmback_hits += ours_hit;
      if (ours_hit != (theirs != EmbreeBaseline::kMissDepth)) {
        ++disagreements;
      } else if (ours_hit) {
        max_error = std::max(max_error, std::abs(double(ours) - theirs) / theirs);
      }
    }
  const uint64_t pixels = embree_depth.size();
  std::printf(
      "%s: %zu triangles, %ux%u px; rays filmback %llu, Embree %llu; hits filmback %llu, Embree "
      "%llu; hit/miss disagreements %llu; max |depth difference| / depth %.2e (tolerance %.0e)\n",
      c.name.c_str(), c.scene.triangle_count(), render.image.width, render.image.height,
      (unsigned long long)render.stats.rays, (unsigned long long)pixels,
      (unsigned long long)filmback_hits, (unsigned long long)embree_hits,
      (unsigned long long)disagreements, max_error, kDepthTolerance);
  return render.stats.rays == pixels && filmback_hits == embree_hits && disagreements == 0 &&
         max_error <= kDepthTolerance;
}

// Wall time is what a user waits for; process CPU time (every thread's) is what the work costs
// and, on a machine that other jobs share, the steadier of the two: a thread waiting for a core
// accrues none. Both are recorded; the ratio is printed for both.
struct Stopwatch {
  using Clock = std::chrono::steady_clock;
  Clock::time_point wall = Clock::now();
  double cpu = process_cpu_seconds();

  static double process_cpu_seconds() {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
  double wall_seconds() const { return std::chrono::duration<double>(Clock::now() - wall).count(); }
  double cpu_seconds() const { return process_cpu_seconds() - cpu; }
};

void set_counters(benchmark::State& state, uint64_t rays, double cpu_seconds) {
  state.SetItemsProcessed(int64_t(rays));  // per wall second of the manual time
  state.counters["rays_per_cpu_s"] = double(rays) / cpu_seconds;
}

// Times RenderJob::run() alone: film allocation, tiles and resolve. `loop_rays_per_s` leaves out
// the film's allocation and resolve (RenderStats::seconds is the tile loop's wall time).
void bench_filmback(benchmark::State& state, const Case& c) {
  uint64_t rays = 0;
  double loop_seconds = 0, cpu_seconds = 0;
  for (auto _ : state) {
    const Stopwatch stopwatch;
    const RenderResult result = c.job->run();
    state.SetIterationTime(stopwatch.wall_seconds());
    cpu_seconds += stopwatch.cpu_seconds();
    rays += result.stats.rays;
    loop_seconds += result.stats.seconds;
  }
  set_counters(state, rays, cpu_seconds);
  state.counters["loop_rays_per_s"] = double(rays) / loop_seconds;
}

void bench_embree(benchmark::State& state, const Case& c) {
  std::vector<float> depth;
  c.baseline->trace(depth, 1);  // allocates the depth buffer outside the timed loop
  uint64_t rays = 0;
  double cpu_seconds = 0;
  for (auto _ : state) {
    const Stopwatch stopwatch;
    benchmark::DoNotOptimize(c.baseline->trace(depth, c.samples_per_pixel));
    state.SetIterationTime(stopwatch.wall_seconds());
    cpu_seconds += stopwatch.cpu_seconds();
    rays += depth.size() * c.samples_per_pixel;
  }
  set_counters(state, rays, cpu_seconds);
}

struct Rates {
  double per_wall_s, per_cpu_s;
  double loop_per_wall_s;  // filmback only: the tile loop without the film's allocation and resolve
};

// The console output, plus each benchmark's rates: their medians over the repetitions when there
// are several (aggregates arrive after a benchmark's repetitions), else its one run.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  RatioReporter() : ConsoleReporter(OO_Tabular) {}  // no colour codes: the output goes into logs
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if (run.run_type == Run::RT_Iteration || median) {
        const auto loop = run.counters.find("loop_rays_per_s");
        rates_[run.run_name.function_name] = {
            run.counters.at("items_per_second"), run.counters.at("rays_per_cpu_s"),
            loop == run.counters.end() ? 0.0 : double(loop->second)};
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
  const std::map<std::string, Rates>& rates() const { return rates_; }

 private:
  std::map<std::string, Rates> rates_;
};

// Keeps in argv what is not ours, for benchmark::ReportUnrecognizedArguments.
Settings parse_settings(int& argc, char** argv) {
  Settings s;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (!parse_flag(arg, "--res=", s.resolution_px) &&
        !parse_flag(arg, "--segments=", s.segments) && !parse_flag(arg, "--threads=", s.threads) &&
        !parse_flag(arg, "--spp=", s.samples_per_pixel))
      argv[kept++] = argv[i];
  }
  argc = kept;
  return s;
}

int run(int argc, char** argv) {
  // Defaults first, so that flags given on the command line override them.
  std::vector<char*> args{argv[0]};
  char repetitions[] = "--benchmark_repetitions=9";
  char interleave[] = "--benchmark_enable_random_interleaving=true";  // noise hits both sides alike
  char min_time[] = "--benchmark_min_time=0.5";
  args.insert(args.end(), {repetitions, interleave, min_time});
  args.insert(args.end(), argv + 1, argv + argc);
  int count = int(args.size());
  benchmark::Initialize(&count, args.data());
  const Settings settings = parse_settings(count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 2;

  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, settings.threads);
  const PluginLoader loader(PluginLoader::default_search_dirs());
  // Agreement is checked at 1 spp, where each pixel's depth is one ray's; the timed cases run
  // 1 spp (the film's per-pixel set-up and resolve weigh most) and 8 spp (they are amortised).
  std::vector<std::unique_ptr<Case>> cases;
  const auto terrain_cells = uint32_t(std::lround(settings.segments / std::sqrt(2.0)));
  for (uint32_t spp : {1u, settings.samples_per_pixel}) {
    const std::string suffix = "/" + std::to_string(spp) + "spp";
    cases.push_back(
        make_case("sphere_in" + suffix, spp, make_sphere_in(settings.segments), settings, loader));
    cases.push_back(
        make_case("terrain" + suffix, spp, make_terrain(terrain_cells), settings, loader));
  }

  std::printf("%u TBB threads\n", settings.threads);
  bool agree = true;
  for (const auto& c : cases)
    if (c->samples_per_pixel == 1) agree = check_agreement(*c) && agree;
  if (!agree) {
    std::fprintf(stderr, "filmback and Embree traced different rays: no timing\n");
    return 1;
  }

  for (const auto& c : cases) {
    benchmark::RegisterBenchmark((c->name + "/filmback").c_str(), bench_filmback, std::cref(*c))
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((c->name + "/embree").c_str(), bench_embree, std::cref(*c))
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  const auto& rates = reporter.rates();
  for (const auto& c : cases) {
    const auto ours = rates.find(c->name + "/filmback"), theirs = rates.find(c->name + "/embree");
    if (ours == rates.end() || theirs == rates.end()) continue;  // filtered out
    const Rates& f = ours->second;
    const Rates& e = theirs->second;
    std::printf(
        "%s medians, Mrays/s: Embree %.3f per wall s, %.3f per CPU s; filmback run() %.3f per wall "
        "s (ratio %.3f), %.3f per CPU s (ratio %.3f); filmback tile loop %.3f per wall s (ratio "
        "%.3f)\n",
        c->name.c_str(), e.per_wall_s * 1e-6, e.per_cpu_s * 1e-6, f.per_wall_s * 1e-6,
        f.per_wall_s / e.per_wall_s, f.per_cpu_s * 1e-6, f.per_cpu_s / e.per_cpu_s,
        f.loop_per_wall_s * 1e-6, f.loop_per_wall_s / e.per_wall_s);
  }
  return 0;
}

}  // namespace
}  // namespace fb::bench

int main(int argc, char** argv) {
  try {
    return fb::bench::run(argc, argv);
  } catch (const fb::UsageError& e) {
    std::fprintf(stderr, "primary_rays_bench: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "primary_rays_bench: %s\n", e.what());
    return 1;
  }
}
