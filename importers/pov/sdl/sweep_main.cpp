// Evaluates POV-Ray scenes with the SDL evaluator and prints one line per scene: ok or the error,
// the objects, lights, what the evaluation used (EvaluationCounts) and the unsupported features
// found. Used for the sample-scene count in
// docs/pov.md: `filmback_pov_sdl_sweep [-frame N] [-tokens N] [-loops N] -L
// /usr/share/povray-3.7/include scene.pov ...`.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "importers/pov/sdl/evaluate.h"

int main(int argc, char** argv) {
  fb::pov::EvaluateOptions base;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "-L" && i + 1 < argc) {
      base.library_paths.push_back(argv[++i]);
    } else if (arg == "-frame" && i + 1 < argc) {
      base.frame_number = std::atof(argv[++i]);
    } else if (arg == "-tokens" && i + 1 < argc) {  // to measure a scene past the limits
      base.limits.tokens = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "-loops" && i + 1 < argc) {
      base.limits.loop_iterations = std::strtoull(argv[++i], nullptr, 10);
    } else {
      scenes.push_back(arg);
    }
  }
  int ok = 0;
  for (const std::string& scene : scenes) {
    fb::pov::EvaluateOptions options = base;
    options.scene_file = scene;
    auto start = std::chrono::steady_clock::now();
    try {
      fb::pov::Scene result = fb::pov::evaluate_pov(options);
      double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::map<std::string, int> features;
      for (const auto& u : result.unsupported)
        ++features[u.feature];
      std::string list;
      for (const auto& [name, count] : features)
        list += " " + name;
      const fb::pov::EvaluationCounts& used = result.counts;
      std::printf(
          "ok %s: %zu objects, %zu lights, %.2f s, used: %llu tokens, %llu loop iterations, "
          "%llu array elements, %llu objects, include depth %u, macro depth %u, nesting %u, "
          "unsupported:%s\n",
          scene.c_str(), result.objects.size(), result.lights.size(), seconds,
          static_cast<unsigned long long>(used.tokens),
          static_cast<unsigned long long>(used.loop_iterations),
          static_cast<unsigned long long>(used.array_elements),
          static_cast<unsigned long long>(used.objects), used.include_depth, used.macro_depth,
          used.nesting, list.c_str());
      ++ok;
    } catch (const std::exception& e) {
      std::printf("FAIL %s: %s\n", scene.c_str(), e.what());
    }
  }
  std::printf("%d of %zu scenes evaluated\n", ok, scenes.size());
  return ok == static_cast<int>(scenes.size()) ? 0 : 1;
}
