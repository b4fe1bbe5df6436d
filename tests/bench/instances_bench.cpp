// Instances kept as instances (core/accel/instancing.h), measured in one run
// (docs/benchmarks.md, "Instances"):
// - build: RenderGeometry for one copy of a 100,000-triangle mesh, against issue 17's forest of
//   10,000 instances of it (10^9 triangles flattened); the goal is the forest under 2x the copy;
// - trace: single rays from inside one copy of the mesh, flattened (what a mesh used once gets)
//   against the same copy traced as an instance, which decides whether a mesh used once is
//   instanced.
// The peak resident memory of the process is printed last. Nothing is asserted: the CTest entry
// runs a tiny size to prove the benchmark builds and runs.
//
//   instances_bench [--segments=N] [--copies=N] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <vector>

#include "core/accel/render_geometry.h"
#include "core/math/random.h"
#include "tests/bench/bench_scenes.h"

namespace fb::bench {
namespace {

struct Settings {
  uint32_t segments = 316;  // the mesh: segments^2 triangles (316 -> 99,856)
  uint32_t copies = 10000;  // the forest's instances, on a square grid 3 m apart
};

// `copies` instances of `mesh`'s one mesh, each turned about +Y and scaled by a hash of its index.
Scene forest(const Scene& mesh, uint32_t copies) {
  Scene scene = mesh;
  scene.instances.clear();
  const uint32_t side = uint32_t(std::ceil(std::sqrt(double(copies))));
  for (uint32_t i = 0; i < copies; ++i) {
    const double turn = unit_float(uint32_t(pcg_hash(i))) * 2 * 3.141592653589793;
    const double size = 0.7 + 0.6 * unit_float(uint32_t(pcg_hash(i, 1)));
    MeshInstance instance;
    instance.world_from_object =
        Transform::translate({3.0 * (i % side), 0, -3.0 * (i / side) - 3}) *
        Transform::rotate({0, std::sin(turn / 2), 0, std::cos(turn / 2)}) *
        Transform::scale({size, size, size});
    scene.instances.push_back(instance);
  }
  return scene;
}

void build(benchmark::State& state, const Scene& scene, Instancing instancing) {
  size_t triangles = 0;
  for (auto _ : state) {
    const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{}, instancing);
    triangles = geometry.triangle_count();
  }
  state.counters["triangles_rendered"] = double(triangles);
}

// Rays from the mesh's centre in 65,536 hashed directions: each hits the star-shaped surface once.
void trace(benchmark::State& state, const Scene& scene, Instancing instancing) {
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{}, instancing);
  std::vector<fb_ray> rays(65536);
  for (uint32_t i = 0; i < rays.size(); ++i) {
    const float z = 1 - 2 * unit_float(uint32_t(pcg_hash(i, 2)));
    const float phi = 6.2831853f * unit_float(uint32_t(pcg_hash(i, 3)));
    const float r = std::sqrt(std::max(0.f, 1 - z * z));
    rays[i] = {{0, 0, 0}, {r * std::cos(phi), r * std::sin(phi), z}, 0.f, INFINITY, 0.f};
  }
  size_t hits = 0;
  for (auto _ : state)
    for (const fb_ray& ray : rays) {
      fb_hit hit;
      hits += geometry.intersect(ray, hit);
    }
  benchmark::DoNotOptimize(hits);
  state.counters["Mrays/s"] = benchmark::Counter(double(state.iterations()) * rays.size() / 1e6,
                                                 benchmark::Counter::kIsRate);
}

uint32_t flag(std::string_view arg, std::string_view name, uint32_t fallback) {
  if (arg.substr(0, name.size()) != name) return fallback;
  uint32_t value = fallback;
  std::from_chars(arg.data() + name.size(), arg.data() + arg.size(), value);
  return value;
}

}  // namespace
}  // namespace fb::bench

int main(int argc, char** argv) {
  using namespace fb;
  using namespace fb::bench;
  Settings settings;
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    settings.segments = flag(arg, "--segments=", settings.segments);
    settings.copies = flag(arg, "--copies=", settings.copies);
    if (arg.substr(0, 11) != "--segments=" && arg.substr(0, 9) != "--copies=")
      rest.push_back(argv[i]);
  }
  int rest_count = int(rest.size());
  benchmark::Initialize(&rest_count, rest.data());
  const Scene one = make_sphere_in(settings.segments);
  const Scene many = forest(one, settings.copies);
  benchmark::RegisterBenchmark("build/one_copy", build, std::cref(one), Instancing::kRepeated)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("build/forest", build, std::cref(many), Instancing::kRepeated)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("trace/once_flattened", trace, std::cref(one), Instancing::kRepeated)
      ->UseRealTime();
  benchmark::RegisterBenchmark("trace/once_instanced", trace, std::cref(one), Instancing::kAlways)
      ->UseRealTime();
  benchmark::RunSpecifiedBenchmarks();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("mesh %zu triangles, forest %u copies; peak resident memory %.1f MiB\n",
              one.meshes[0].triangle_count(), settings.copies, double(usage.ru_maxrss) / 1024);
  benchmark::Shutdown();
  return 0;
}
