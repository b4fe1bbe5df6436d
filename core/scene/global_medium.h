// A medium filling the whole scene: POV-Ray's fog (POV-Ray 3.7 reference, "Fog"; docs/pov.md
// "Fog"). Physically a homogeneous medium that absorbs with extinction sigma = density /
// distance_m and emits sigma * colour, without scattering: along a segment of optical depth tau
// its exact solution is the blend L = e^-tau L_behind + (1 - e^-tau) colour, which is what
// POV-Ray computes. POV-Ray's filter and transmit of the fog colour, which no medium has, are
// kept for the integrators that blend as POV-Ray does (core/render/global_medium_segment.h).
#pragma once

#include <filmback/vec.h>

namespace fb {

// How the density varies: the same everywhere, or POV-Ray's ground fog: 1 at and below the
// height `offset_m` along `up`, 1 / (1 + h^2) above, h = (height - offset_m) / altitude_m.
enum class MediumProfile { kConstant, kGround };

struct GlobalMedium {
  MediumProfile profile = MediumProfile::kConstant;
  double distance_m = 1;      // at full density: the distance that leaves e^-1 of the light
  Rgb colour{0.f, 0.f, 0.f};  // linear: the radiance a thick layer of it shows
  float filter = 0.f;         // POV-Ray: the light behind is also tinted by `colour` this much
  float transmit = 0.f;       // POV-Ray: at least this much of the light behind comes through
  Vec3d up{0, 1, 0};          // kGround: unit, world space
  double offset_m = 0, altitude_m = 1;  // kGround
};

}  // namespace fb
