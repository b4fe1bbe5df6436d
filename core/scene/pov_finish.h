// POV-Ray's finish and interior as a .pov scene wrote them, kept beside the physical Material the
// importer maps them to (docs/pov.md, "Finishes and interiors"), for the `povray` integrator, which
// lights a surface as POV-Ray 3.7 does (docs/pov.md, "The povray integrator"). Colours are decoded
// to linear as pigments are; amounts are as written.
#pragma once

#include <cstdint>

#include <filmback/vec.h>

namespace fb {

struct PovFinish {
  Rgb pigment{1.f, 1.f, 1.f};  // the pigment's colour (a pattern's average)
  // The base colour at a hit is the pigment there times this (diffuse, or 1 for metals and
  // transparent pigments); 0: use `pigment`.
  float pigment_scale = 1.f;
  float filter = 0.f, transmit = 0.f;  // a plain pigment's; 0 for a patterned one
  // The probability that the host keeps a hit on this material (its alpha when blended: a plain
  // pigment's transmit without refraction is coverage 1 - transmit, docs/pov.md); 1 otherwise.
  float coverage = 1.f;
  Rgb ambient{0.1f, 0.1f, 0.1f};  // times the scene's ambient_light
  Rgb emission{0.f, 0.f, 0.f};
  float diffuse = 0.6f, brilliance = 1.f;
  float phong = 0.f, phong_size = 40.f;
  float specular = 0.f, roughness = 0.05f;  // Blinn exponent 1 / roughness
  float metallic = 0.f;
  Rgb reflection_min{0.f, 0.f, 0.f}, reflection_max{0.f, 0.f, 0.f};
  float reflection_falloff = 1.f, reflection_exponent = 1.f;
  bool reflection_fresnel = false;
  float reflection_metallic = 0.f;
  float ior = 1.f;  // the interior's
};

// A POV-Ray scene's global_settings that decide how deep its rays go, and in what values POV-Ray
// computes its colours (docs/pov.md, "The povray integrator").
struct PovTracing {
  uint32_t max_trace_level = 5;  // POV-Ray 3.7's default
  double adc_bailout = 1.0 / 255;
  double colour_gamma = 1.0;         // what decoded the scene's colours (c^g)
  Rgb ambient_light{1.f, 1.f, 1.f};  // decoded; PovFinish::ambient is multiplied by it
};

}  // namespace fb
