// Analytic solids and CSG against triangles at equal complexity (issue 17, goal 3: the analytic
// scene at >= 50 % of the triangle scene's samples/s). One scene of CSG objects is rendered as
// analytic solids, and as the same solids tessellated to the tolerance `filmback convert` uses
// (TessellationOptions' defaults): the same objects, pixels, lights, materials and path lengths,
// so that the two renders differ only in what a ray meets. Two integrators: `path` (bounces and
// shadow rays: what a render costs) and `aov` (camera rays only: what the intersection costs).
// Samples per CPU second of the whole process (every thread's time during RenderJob::run) are
// compared by their medians over interleaved repetitions: on a shared machine a thread waiting
// for a core accrues no CPU time, so this is steadier than wall time, which is printed too. The
// ratios are printed last (docs/benchmarks.md, "Analytic solids and CSG").
//
//   filmback_solids_bench [--res=PX] [--grid=N] [--spp=S] [--threads=T] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

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
#include "core/tessellate/tessellate.h"
#include "core/util/diagnostics.h"
#include "core/util/error.h"
#include "tests/bench/bench_flags.h"

namespace fb::bench {
namespace {

struct Settings {
  uint32_t resolution_px = 192;  // the image's width; its height is 3/4 of it
  uint32_t grid = 6;             // grid x grid CSG objects
  uint32_t samples_per_pixel = 4;
  uint32_t threads = 2;
};

// A rotation by `angle_rad` about a unit axis, as a quaternion (x, y, z, w).
Transform rotation(Vec3d axis, double angle_rad) {
  const double s = std::sin(0.5 * angle_rad);
  return Transform::rotate({axis.x * s, axis.y * s, axis.z * s, std::cos(0.5 * angle_rad)});
}

Solid primitive(SolidKind kind, const Transform& world_from_object, std::string name) {
  Solid s;
  s.kind = kind;
  s.name = std::move(name);
  s.world_from_object = world_from_object;
  return s;
}

// A die: a box rounded by a sphere, bored through by a cylinder along y (POV-Ray's classic
// difference { intersection { box sphere } cylinder }), four primitives; the objects stand on a
// ground box and a sun lights them, so that shadow rays meet the CSG too.
Scene make_csg_scene(uint32_t grid) {
  Scene scene;
  Material grey;
  grey.name = "grey";
  grey.base_color = {0.7f, 0.7f, 0.7f};
  grey.roughness = 0.4f;
  scene.materials.push_back(grey);
  for (uint32_t i = 0; i < grid * grid; ++i) {
    const Vec3d centre{3.0 * (i % grid) - 1.5 * (grid - 1), 1, 3.0 * (i / grid) - 1.5 * (grid - 1)};
    const std::string name = "die " + std::to_string(i);
    Solid rounded;
    rounded.kind = SolidKind::kIntersection;
    rounded.name = name;
    rounded.children = {
        primitive(SolidKind::kBox, Transform::translate(centre), name),
        primitive(SolidKind::kSphere,
                  Transform::translate(centre) * Transform::scale({1.4, 1.4, 1.4}), name)};
    Solid bore =
        primitive(SolidKind::kCylinder,
                  Transform::translate(centre + Vec3d{0, -2, 0}) *
                      rotation({1, 0, 0}, -1.5707963267948966) * Transform::scale({0.5, 0.5, 4}),
                  name);
    bore.inverse = true;
    Solid die;
    die.kind = SolidKind::kIntersection;
    die.name = name;
    die.children = {std::move(rounded), std::move(bore)};
    scene.solids.push_back(std::move(die));
  }
  const double half = 1.5 * grid + 2;
  scene.solids.push_back(primitive(
      SolidKind::kBox, Transform::translate({0, -0.5, 0}) * Transform::scale({half, 0.5, half}),
      "ground"));
  Light sun;
  sun.name = "sun";
  sun.type = LightType::kDirectional;
  sun.intensity = {3.f, 3.f, 3.f};
  sun.world_from_light = rotation({0, 1, 0}, 0.5) * rotation({1, 0, 0}, -0.9);
  scene.lights.push_back(sun);
  scene.background = {0.3f, 0.35f, 0.4f};
  SceneCamera camera;
  camera.name = "bench";
  camera.source = "procedural";
  camera.physical.focal_length_mm = 30;
  camera.world_from_camera =
      Transform::translate({0, 2.2 * grid, 2.4 * grid}) * rotation({1, 0, 0}, -0.75);
  scene.cameras.push_back(camera);
  return scene;
}

struct Case {
  std::string name;  // "analytic/path", ...
  const Scene* scene;
  std::unique_ptr<RenderJob> job;
};

double process_cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

void bench_render(benchmark::State& state, const Case& c) {
  uint64_t samples = 0;
  double wall_seconds = 0;
  for (auto _ : state) {
    const double cpu = process_cpu_seconds();
    const RenderResult result = c.job->run();
    state.SetIterationTime(process_cpu_seconds() - cpu);
    samples += result.stats.samples;
    wall_seconds += result.stats.seconds;
  }
  state.SetItemsProcessed(int64_t(samples));  // per CPU second: the manual time
  state.counters["samples_per_wall_s"] = double(samples) / wall_seconds;
}

// The console output, plus each case's median samples/s over the repetitions (or its one run).
class MedianReporter : public benchmark::ConsoleReporter {
 public:
  MedianReporter() : ConsoleReporter(OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs)
      if (run.run_type == Run::RT_Iteration ||
          (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median"))
        samples_per_s_[run.run_name.function_name] = run.counters.at("items_per_second");
    ConsoleReporter::ReportRuns(runs);
  }
  const std::map<std::string, double>& samples_per_s() const { return samples_per_s_; }

 private:
  std::map<std::string, double> samples_per_s_;
};

int run(int argc, char** argv) {
  std::vector<char*> args{argv[0]};
  char repetitions[] = "--benchmark_repetitions=7";
  char interleave[] = "--benchmark_enable_random_interleaving=true";  // noise hits both alike
  char min_time[] = "--benchmark_min_time=0.5";
  args.insert(args.end(), {repetitions, interleave, min_time});
  args.insert(args.end(), argv + 1, argv + argc);
  int count = int(args.size());
  benchmark::Initialize(&count, args.data());
  Settings settings;
  int kept = 1;
  for (int i = 1; i < count; ++i) {
    const std::string_view arg = args[size_t(i)];
    if (!parse_flag(arg, "--res=", settings.resolution_px) &&
        !parse_flag(arg, "--grid=", settings.grid) &&
        !parse_flag(arg, "--spp=", settings.samples_per_pixel) &&
        !parse_flag(arg, "--threads=", settings.threads))
      args[size_t(kept++)] = args[size_t(i)];
  }
  count = kept;
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 2;

  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, settings.threads);
  const PluginLoader loader(PluginLoader::default_search_dirs());
  RenderOptions options;
  options.width = settings.resolution_px;
  options.height = settings.resolution_px * 3 / 4;
  options.samples_per_pixel = settings.samples_per_pixel;
  options.show_progress = false;

  const Scene analytic = make_csg_scene(settings.grid);
  Scene triangles = make_csg_scene(settings.grid);
  Diagnostics diagnostics;
  tessellate_solids(triangles, TessellationOptions(), diagnostics);
  std::vector<std::unique_ptr<Case>> cases;
  for (const char* integrator : {"path", "aov"})
    for (const Scene* scene : {&analytic, static_cast<const Scene*>(&triangles)}) {
      const std::string name =
          std::string(scene == &analytic ? "analytic/" : "triangles/") + integrator;
      cases.push_back(std::make_unique<Case>(Case{name, scene, {}}));
    }
  // The same image within noise, or the comparison is void: the mean pixel values printed.
  for (const auto& c : cases) {
    options.integrator = c->name.substr(c->name.find('/') + 1);
    c->job = std::make_unique<RenderJob>(*c->scene, options, loader);
    const RenderResult first = c->job->run();
    double sum = 0;
    for (uint32_t y = 0; y < first.image.height; ++y)
      for (uint32_t x = 0; x < first.image.width; ++x)
        sum += first.image.at(x, y, 0) + first.image.at(x, y, 1) + first.image.at(x, y, 2);
    std::printf("%s: %zu solids, %zu triangles, %ux%u px, %u spp; mean pixel value %.5f\n",
                c->name.c_str(), c->scene->solids.size(), c->scene->triangle_count(),
                first.image.width, first.image.height, settings.samples_per_pixel,
                sum / (3.0 * first.image.width * first.image.height));
    benchmark::RegisterBenchmark(c->name.c_str(), bench_render, std::cref(*c))
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  const auto& rates = reporter.samples_per_s();
  for (const char* integrator : {"path", "aov"}) {
    const auto ours = rates.find(std::string("analytic/") + integrator),
               theirs = rates.find(std::string("triangles/") + integrator);
    if (ours == rates.end() || theirs == rates.end()) continue;  // filtered out
    std::printf(
        "%s: analytic/triangles medians: %.3f M samples/cpu-s / %.3f M samples/cpu-s = %.3f\n",
        integrator, ours->second * 1e-6, theirs->second * 1e-6, ours->second / theirs->second);
  }
  return 0;
}

}  // namespace
}  // namespace fb::bench

int main(int argc, char** argv) {
  try {
    return fb::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "filmback_solids_bench: %s\n", e.what());
    return 1;
  }
}
