// Texture filtering by the ray's footprint (core/texture/ray_footprint.h): time and error of
// renders of a checkered ground receding to the horizon, at the finest level only (as before issue
// 17) and filtered by the footprint, against a reference supersampled at the finest level
// (docs/benchmarks.md, "Texture filtering"). The ground emits its texture and the path tracer shows
// emitters only, so the error is the texture's alone. Every job is built before timing (images
// decoded, MIP levels made); the benchmarks time RenderJob::run. Use
// --benchmark_enable_random_interleaving and repetitions for ratios on a loaded machine.
//
//   texture_filtering_bench [--res=W] [--reference-spp=N] [google benchmark flags]
#include <benchmark/benchmark.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/render/render_job.h"
#include "support/plugins.h"
#include "support/textured_quad.h"

namespace fb::bench {
namespace {

struct Settings {
  uint32_t width_px = 320;
  uint32_t reference_spp = 1024;
};

RenderOptions options(const Settings& settings, uint32_t spp, bool footprint, uint64_t seed) {
  return test::texture_render_options(settings.width_px, settings.width_px * 5 / 8, spp, footprint,
                                      seed);
}

double rms_difference(const Image& a, const Image& b) {
  double sum = 0;
  const size_t n = size_t(a.width) * a.height;
  for (size_t i = 0; i < n; ++i) {
    const double d = double(a.at(i % a.width, i / a.width, 0)) - b.at(i % a.width, i / a.width, 0);
    sum += d * d;
  }
  return std::sqrt(sum / n);
}

bool parse_flag(std::string_view arg, std::string_view name, uint32_t& value) {
  if (!arg.starts_with(name)) return false;
  arg.remove_prefix(name.size());
  return std::from_chars(arg.data(), arg.data() + arg.size(), value).ec == std::errc{};
}

}  // namespace
}  // namespace fb::bench

int main(int argc, char** argv) {
  using namespace fb;
  bench::Settings settings;
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i)
    if (!bench::parse_flag(argv[i], "--res=", settings.width_px) &&
        !bench::parse_flag(argv[i], "--reference-spp=", settings.reference_spp))
      rest.push_back(argv[i]);
  int rest_count = int(rest.size());
  benchmark::Initialize(&rest_count, rest.data());

  // 1 km wide, 500 m deep, 1 m below the camera; a 1024-texel tile of 32-texel checks per 4 m.
  static const Scene scene = test::textured_quad(
      {{-500.f, -1.f, -0.2f}, {500.f, -1.f, -0.2f}, {500.f, -1.f, -500.f}, {-500.f, -1.f, -500.f}},
      true, 4.f, 1024, 32, 1.6,
      std::filesystem::temp_directory_path() / "filmback-texture-filtering-bench.gltf");
  const Image reference =
      RenderJob(scene, bench::options(settings, settings.reference_spp, false, 7), test::loader())
          .run()
          .image;
  const double reference_noise =
      bench::rms_difference(
          reference, RenderJob(scene, bench::options(settings, settings.reference_spp, false, 8),
                               test::loader())
                         .run()
                         .image) /
      std::sqrt(2.0);
  std::printf("reference: %u spp at the finest level, its own RMS noise %.4f\n",
              settings.reference_spp, reference_noise);
  static std::vector<std::unique_ptr<RenderJob>> jobs;
  for (const uint32_t spp : {1u, 4u, 16u})
    for (const bool footprint : {false, true}) {
      jobs.push_back(std::make_unique<RenderJob>(scene, bench::options(settings, spp, footprint, 1),
                                                 test::loader()));
      const RenderJob& job = *jobs.back();
      const double error = bench::rms_difference(job.run().image, reference);
      const std::string name =
          std::string(footprint ? "footprint" : "finest") + "/" + std::to_string(spp) + "spp";
      std::printf("%-16s RMS error %.4f\n", name.c_str(), error);
      benchmark::RegisterBenchmark(name.c_str(),
                                   [&job, error](benchmark::State& state) {
                                     for (auto _ : state)
                                       benchmark::DoNotOptimize(job.run());
                                     state.counters["rms_error"] = error;
                                   })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
