// A solid (3-D) texture: a colour as a function of the position in the texture's own space, as
// POV-Ray's pigments define it (POV-Ray 3.7 manual, "Patterns"). importers/pov makes them;
// core/texture/solid_pattern.h evaluates them at every hit (docs/pov.md, "Appearance").
#pragma once

#include <vector>

#include <filmback/vec.h>

#include "core/math/transform.h"

namespace fb {

// A colour with POV-Ray's two transparencies: `filter` lets light through tinted by the colour,
// `transmit` lets it through unchanged. Linear.
struct SolidColour {
  Rgb rgb{0.f, 0.f, 0.f};
  float filter = 0.f, transmit = 0.f;
};

struct SolidColourStop {
  float value = 0.f;  // in [0, 1], non-decreasing along the map
  SolidColour colour;
};

enum class SolidPatternKind {
  kSolid,  // `colour` everywhere
  // List patterns: the value picks an entry of `list` (checker 2, hexagon 3, brick 2).
  kChecker,
  kHexagon,
  kBrick,
  // Value patterns in [0, 1], looked up in `colour_map`.
  kGradient,
  kBozo,
  kSpotted,
  kBumps,
  kGranite,
  kMarble,
  kWood,
  kAgate,
  kLeopard,
  kOnion,
  kRadial,
  kSpiral1,
  kSpiral2,
  kWaves,
  kRipples,
  kWrinkles,
  kDents,
  kCrackle,
  kCells,
};

// POV-Ray's wave types: how a value pattern's raw value becomes the colour map's index.
enum class SolidWave { kRamp, kTriangle, kSine, kScallop, kCubic, kPoly };

struct SolidPattern {
  SolidPatternKind kind = SolidPatternKind::kSolid;
  SolidColour colour;                       // kSolid
  std::vector<SolidColourStop> colour_map;  // value patterns; empty: black to white
  std::vector<SolidPattern> list;           // list patterns, each with its own pattern space
  Transform pattern_from_world;             // world: filmback's right-handed world, metres
  // Turbulence (POV-Ray's classic warp): the point moves by `turbulence` times a fractal vector
  // noise of `octaves` octaves, each `lambda` times the frequency and `omega` times the amplitude
  // of the last. Marble, wood, agate and the spirals use it inside the pattern instead.
  Vec3d turbulence{0, 0, 0};
  int octaves = 6;
  double omega = 0.5, lambda = 2.0;
  double frequency = 1, phase = 0;
  SolidWave wave = SolidWave::kRamp;
  double wave_exponent = 1;  // kPoly
  Vec3d gradient{0, 1, 0};   // kGradient's direction, unit
  Vec3d brick_size{8, 3, 4.5};
  double mortar = 0.5;
  int spiral_arms = 1;
  double agate_turbulence = 1;  // agate_turb
};

}  // namespace fb
