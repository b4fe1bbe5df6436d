#include "importers/pov/sdl/solid_pigment.h"

#include <algorithm>
#include <cmath>

namespace fb::pov {
namespace {

SolidColour solid_colour(const Colour& c, double gamma) {
  return {decode(c, gamma), float(std::clamp(c.filter, 0.0, 1.0)),
          float(std::clamp(c.transmit, 0.0, 1.0))};
}

}  // namespace

Rgb decode(const Colour& c, double gamma) {
  const auto channel = [gamma](double v) { return float(std::pow(std::max(v, 0.0), gamma)); };
  return {channel(c.r), channel(c.g), channel(c.b)};
}

SolidPattern to_solid(const Pigment& p, double gamma, const Transform& pov_from_input) {
  SolidPattern s;
  // an averaged pattern is its average colour
  s.kind = p.averaged ? SolidPatternKind::kSolid : p.pattern;
  s.colour = solid_colour(p.colour, gamma);
  if (s.kind == SolidPatternKind::kSolid) return s;
  s.pattern_from_world = p.pattern_from_world * pov_from_input;
  for (const ColourMapEntry& e : p.colour_map)
    s.colour_map.push_back({float(std::clamp(e.value, 0.0, 1.0)), solid_colour(e.colour, gamma)});
  for (const Pigment& entry : p.list)
    s.list.push_back(to_solid(entry, gamma, pov_from_input));
  s.image_map = p.image_map;  // its image index is the same in both scenes (import_pov)
  static_cast<SolidPatternModifiers&>(s) = p;
  // Marble, wood and the spirals default to triangle_wave (checked against POV-Ray's renders,
  // pov_appearance_test). pov::Pigment does not say whether a ramp_wave was written, so ramp
  // means the default here.
  if ((s.kind == SolidPatternKind::kMarble || s.kind == SolidPatternKind::kWood ||
       s.kind == SolidPatternKind::kSpiral1 || s.kind == SolidPatternKind::kSpiral2) &&
      s.wave == SolidWave::kRamp)
    s.wave = SolidWave::kTriangle;
  // POV-Ray normalises the gradient vector (checked: `gradient <2,0,0>` repeats every unit).
  const double len = std::sqrt(dot(p.gradient, p.gradient));
  s.gradient = len > 0 ? p.gradient / len : Vec3d{0, 0, 0};
  return s;
}

}  // namespace fb::pov
