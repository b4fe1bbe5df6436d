// The inner part of a spindle torus between two planes: POV-Ray's lemon, and the collar that joins
// an ovus's two spheres (POV-Ray 3.8 reference, "Lemon"; 3.7 reference, "Ovus"). In its canonical
// space the torus's minor circle has radius 1, its centre at height 0 and at `major` on the far
// side of the z axis, so the set is
//   (rho + major)^2 + z^2 <= 1,  z_low <= z <= z_high,  rho = sqrt(x^2 + y^2),
// the points within 1 of every point of the circle of radius `major` about z: convex, with
// cusps on the axis at z = +-sqrt(1 - major^2) (major = 0: the unit sphere).
#pragma once

#include <filmback/vec.h>

#include "core/math/bounds.h"

namespace fb {

struct Lemon {
  double major = 0;  // 0 <= major < 1
  double z_low = -1, z_high = 1;
};

// Below this `major` the torus's quartic holds two surfaces closer than its roots can be told
// apart: the lemon is drawn as the unit sphere, off by at most this much.
constexpr double kLemonLeastMajor = 1e-6;

// The largest rho within the slab, <= 0 when the slab misses the lemon.
double lemon_widest(const Lemon& lemon);
Bounds3d lemon_bounds(const Lemon& lemon);
// (rho + major)^2 + z^2 - 1: < 0 inside (the slab aside).
double lemon_value(const Lemon& lemon, Vec3d p);
// Its gradient, outward on the curved surface (undefined on the axis, at the cusps).
Vec3d lemon_gradient(const Lemon& lemon, Vec3d p);
// The torus's quartic (rho^2 + z^2 + major^2 - 1)^2 - 4 major^2 rho^2 along o + s d, c[0] + c[1]
// s + ... + c[4] s^4: zero on the lemon and on the rest of the spindle torus (the "apple").
void lemon_quartic(const Lemon& lemon, Vec3d o, Vec3d d, double c[5]);

}  // namespace fb
