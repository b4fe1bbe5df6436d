// A homogeneous participating medium filling the inside of a closed surface: POV-Ray's interior
// media (POV-Ray 3.7 reference, "Media"; docs/pov.md "Media"), coefficients per metre (POV-Ray
// units taken as metres). A ray is in it between its entry into the surface and its exit.
#pragma once

#include <filmback/vec.h>

namespace fb {

struct InteriorMedium {
  Rgb absorption{0.f, 0.f, 0.f};  // sigma_a, m^-1
  Rgb scattering{0.f, 0.f, 0.f};  // sigma_s, m^-1; isotropic
  // Radiance added per metre of path, W sr^-1 m^-3: POV-Ray's emission, the physical emission
  // coefficient (sigma_a L_e in pbrt's terms).
  Rgb emission{0.f, 0.f, 0.f};
  // What POV-Ray attenuates by: absorption + extinction * scattering (its scattering's
  // `extinction`, 1 by default, where physics has 1).
  Rgb povray_extinction{0.f, 0.f, 0.f};
  // How many points along a segment POV-Ray 3.7 sums the medium's light at: its method 3 is a
  // left Riemann sum of max(2, samples / 2 + 1) points per interval (measured, docs/pov.md
  // "Media"), times its intervals.
  uint32_t povray_points = 6;
};

}  // namespace fb
