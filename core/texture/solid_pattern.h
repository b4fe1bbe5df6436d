// Evaluates solid textures (core/scene/solid_texture.h) the way POV-Ray 3.7 defines its patterns
// (POV-Ray 3.7 manual, "Patterns"; source/core/material/pattern.cpp for the exact formulas). The
// one deliberate difference is the noise: POV-Ray's Noise() is a lattice noise of its own with
// tables we do not copy; ours is Perlin's improved noise (Perlin 2002, "Improving Noise") scaled
// to POV-Ray's mean and spread, so bozo, granite, agate ... look alike but differ point by point
// (docs/pov.md, "Appearance").
#pragma once

#include <array>

#include <filmback/vec.h>

#include "core/scene/solid_texture.h"
#include "core/texture/texture_images.h"

namespace fb {

// The texture's colour at a world-space point (filter and transmit included). Image maps read
// `images`; without them (a sky baked before any render) they stand in with their `colour`.
SolidColour evaluate_solid(const SolidPattern& pattern, Vec3d world_point,
                           const TextureImages* images = nullptr);

// The pieces, exposed for tests.
namespace solid {

// POV-Ray's waves and ripples sum circular waves from ten sources near the origin
// (TraceThreadData's waveSources), each with a frequency factor (waves only).
constexpr int kWaveSources = 10;
struct WaveSource {
  Vec3d centre;
  double frequency;
};
const std::array<WaveSource, kWaveSources>& wave_sources();

// Lattice noise in [0, 1] with POV-Ray's mean (0.5) and standard deviation (0.132, measured on
// POV-Ray 3.7's bozo over a 40 x 40 unit plane).
double noise(Vec3d p);
// A vector noise with components in [-1, 1] (POV-Ray's DNoise).
Vec3d vector_noise(Vec3d p);
// POV-Ray's Turbulence(): noise summed over octaves, each lambda times the frequency and omega
// times the amplitude of the one before.
double turbulence(Vec3d p, int octaves, double omega, double lambda);
Vec3d vector_turbulence(Vec3d p, int octaves, double omega, double lambda);
// The pattern's raw value before frequency, phase and wave (list patterns: the entry's index).
double raw_value(const SolidPattern& pattern, Vec3d pattern_point);
// frequency, phase and the wave shape applied to a raw value (POV-Ray's
// ContinuousPattern::Evaluate).
double shape_value(const SolidPattern& pattern, double raw);
// The pattern point moved by the classic turbulence warp (none for the patterns that turbulate
// inside: marble, wood, agate, the spirals).
Vec3d warped_point(const SolidPattern& pattern, Vec3d pattern_point);
// The colour map at `value`: linear between stops, clamped to the first and last.
SolidColour colour_at(const std::vector<SolidColourStop>& map, double value);

}  // namespace solid
}  // namespace fb
