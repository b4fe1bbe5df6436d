// NaN and Inf from the file (scenes/hard/README.md, "bad input"): in vertex data and in material
// values they are refused at import, naming the file, the JSON path and what was expected; a
// finite but huge normal shades as its direction.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/util/diagnostics.h"
#include "core/util/error.h"
#include "hard_case.h"
#include "importers/gltf/gltf_importer.h"

namespace fb {
namespace {

using test::report_case;

// Imports scenes/hard/<file>, which must fail; returns the message.
std::string import_error(const std::string& file) {
  Diagnostics diagnostics;
  try {
    import_gltf(std::filesystem::path(FILMBACK_HARD_SCENES) / file, diagnostics);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << file << " imported";
  return "";
}

TEST(BadInput, NonFiniteVertexDataAndMaterialValuesAreRefusedWithTheirPath) {
  struct Case {
    const char* file;
    std::vector<const char*> parts;
  };
  for (const Case& c :
       {Case{"nan_position.gltf",
             {"meshes[0].primitives[0].attributes.POSITION (accessors[0])", "element 2",
              "not a finite number"}},
        Case{"inf_normal.gltf",
             {"meshes[0].primitives[0].attributes.NORMAL (accessors[1])", "element 1",
              "not a finite number"}},
        Case{"inf_emission.gltf",
             {"materials[0]", "emissiveFactor x emissiveStrength", "must be finite"}}}) {
    const test::Stopwatch clock;
    const std::string message = import_error(c.file);
    size_t missing = 0;
    for (const char* part : c.parts)
      missing += message.find(part) == std::string::npos;
    missing += message.rfind(std::string(FILMBACK_HARD_SCENES) + "/" + c.file, 0) != 0;
    report_case(c.file, 0, double(missing), 0,
                "parts of 'file: JSON path: what' missing from: " + message, clock.seconds());
  }
}

// NORMAL (0, 3e38, 1) at one corner: finite, but squaring it overflows float. Normals reach
// render space normalised in double (core/accel/render_geometry.cpp), so it shades as (0, 1, 0):
// the image is the one with that normal written out.
TEST(BadInput, HugeNormalsShadeAsTheirDirection) {
  const Scene scene = test::load_hard_scene("huge_normal.gltf");
  Scene unit = scene;
  unit.meshes.at(0).normals.at(1) = {0, 1, 0};
  RenderOptions options;
  options.samples_per_pixel = 16;
  const test::TimedRender r = test::render_timed(scene, options),
                          reference = test::render_timed(unit, options);
  double worst = 0, brightest = 0;
  for (size_t i = 0; i < r.result.image.pixels.size(); ++i) {
    worst = std::max(worst,
                     double(std::abs(r.result.image.pixels[i] - reference.result.image.pixels[i])));
    brightest = std::max(brightest, double(reference.result.image.pixels[i]));
  }
  ASSERT_GT(brightest, 0.0);
  report_case("huge_normal.gltf", r.result.stats.dropped_samples, worst / brightest, 1e-6,
              "max |pixel - with the unit normal| / brightest pixel", r.seconds);
}

}  // namespace
}  // namespace fb
