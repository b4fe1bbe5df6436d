// POV-Ray textures, lights and sky as filmback's physically based materials, lights and world,
// by the mapping docs/pov.md ("Appearance") writes down: a POV-Ray scene lit only by its light
// sources renders in filmback as in POV-Ray's linear output, and what physics lacks (POV-Ray's
// light fading, spotlight curve, shadowless lights) is asked for through Light's opt-in fields.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"
#include "importers/pov/pov_scene.h"

namespace fb::pov {

// The exponent that decodes the scene's colours to linear: assumed_gamma when the scene gives
// it; otherwise 1 (linear) for #version 3.7 and later, and 2.2 for older scenes, which POV-Ray
// renders without gamma handling, so that their colours were chosen as display values.
double colour_gamma(const Scene& scene);

// A POV-Ray texture (and interior) as a filmback material (docs/pov.md, "Appearance"). Exposed
// for tests; MaterialTable is what converters use.
Material make_material(const Texture& texture, const std::optional<Interior>& interior,
                       double gamma, const Colour& ambient_light);

// Materials of one converted scene: each distinct texture + interior once in out.materials.
class MaterialTable {
 public:
  MaterialTable(const Scene& scene, fb::Scene& out, Diagnostics& diagnostics);
  // The index in out.materials; what the texture uses that is not rendered is reported once per
  // feature, with where it was first met.
  uint32_t material(const Texture& texture, const std::optional<Interior>& interior);

 private:
  void report(const Texture& texture);
  fb::Scene& out_;
  Diagnostics& diagnostics_;
  double gamma_;
  Colour ambient_light_;
  std::map<std::string, uint32_t> index_;  // by the material's content
  std::set<std::string> reported_;
};

// light_source statements as filmback lights with POV-Ray's semantics (LightDecay::kPovRay,
// SpotFalloff::kPov, area grids, shadowless), intensity pi times the colour.
void convert_lights(const Scene& scene, fb::Scene& out, Diagnostics& diagnostics);

// `background` as Scene::background; a sky_sphere as an environment map of kSkyWidth x kSkyHeight
// texels, its pigments layered over the background colour.
void convert_environment(const Scene& scene, fb::Scene& out, Diagnostics& diagnostics);
constexpr uint32_t kSkyWidth = 512, kSkyHeight = 256;

}  // namespace fb::pov
