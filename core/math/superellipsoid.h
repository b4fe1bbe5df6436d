// POV-Ray's superellipsoid { <e, n> } (POV-Ray 3.7 reference, "Superellipsoid"): the set
// f(p) = (|x|^(2/e) + |y|^(2/e))^(e/n) + |z|^(2/n) - 1 <= 0 within the unit box. Its implicit
// function, outward gradient, parametric surface points, and its crossings along a ray, for the
// intersector (core/accel/solid_intersect) and the tessellator (core/tessellate).
#pragma once

#include <filmback/vec.h>

namespace fb {

struct SuperellipsoidExponents {
  double e = 1, n = 1;  // east-west (the xy sections) and north-south (along z), both > 0
};

// f(p): negative inside, zero on the surface, positive outside (and everywhere outside the unit
// box: |x| > 1 or |z| > 1 alone makes it positive).
double superellipsoid_value(SuperellipsoidExponents s, Vec3d p);

// The direction of grad f at p (its length is arbitrary): outward, finite, and non-zero on the
// surface; computed through logarithms so that large exponents neither overflow nor give 0 * inf.
Vec3d superellipsoid_gradient(SuperellipsoidExponents s, Vec3d p);

// The surface point at latitude eta in [-pi/2, pi/2] and longitude omega: x = c(eta)^n c(omega)^e,
// y = c(eta)^n s(omega)^e, z = s(eta)^n with signed powers (Barr 1981).
Vec3d superellipsoid_point(SuperellipsoidExponents s, double eta, double omega);

// The most crossings superellipsoid_crossings reports: a line meets the star-shaped set in at
// most a few spans (two arms and the centre of a star with concave sides); more are dropped.
constexpr int kSuperellipsoidMaxCrossings = 8;

// The ray's parameters t in (lo, hi) where f(o + t d) changes sign, ascending, into `roots`
// (room for kSuperellipsoidMaxCrossings); returns how many, always even when f > 0 at lo and hi.
// The interval is cut at the planes x = 0, y = 0, z = 0 and x = +-y, across which f's pieces are
// smooth; each piece is sampled at kSuperellipsoidSamples points, a sign change between two is
// refined by bisection to the last bits of a double, and a sampled local minimum above zero is
// searched (golden section) for a dip below it, so grazing rays are not lost between samples.
int superellipsoid_crossings(SuperellipsoidExponents s, Vec3d o, Vec3d d, double lo, double hi,
                             double* roots);

}  // namespace fb
