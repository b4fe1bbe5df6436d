// POV-Ray's julia_fractal (POV-Ray 3.7 reference, "Julia Fractal"; fractal.cpp, quatern.cpp,
// hcmplx.cpp): a 3-D slice of a 4-D Julia set. A point p of the object space is the 4-D number
// (x, y, z, w) on the slice hyperplane slice . (x, y, z, w) = distance; it is inside when the
// iterates z_0 = that number, z_{k+1} = z_k^m + c (m = 2: sqr, 3: cube; quaternion or
// hypercomplex products) stay within the escape sphere |z_k|^2 <= exit_value for k < max_iteration
// (POV-Ray's Iteration: z_max_iteration itself is not tested). The set lies within the bounding
// sphere of `radius` about the origin: outside it, |z_0| >= |p| already escapes.
//
// The boundary near a point where z_k first escapes is the level |z_k(p)|^2 = exit_value, so its
// outward normal is that function's gradient, exact (POV-Ray's Normal_Calc_Julia computes the
// same Jacobian product). A ray marches by a distance estimate to the escape sphere of the iterate
// that escaped, (ln|z_k| - ln R) / (2 |grad ln|z_k||) with the gradient bounded by the running
// derivative |z_k'|, never less than 1 / precision, and bisects
// each step that changes side. (POV-Ray's estimate is the distance to the limit set, which a
// finite max_iteration's larger set can be nearer than.)
// docs/pov.md, "Julia fractal".
#pragma once

#include <cstdint>

#include <filmback/vec.h>

#include "core/math/bounds.h"

namespace fb {

enum class JuliaAlgebra : uint8_t { kQuaternion, kHypercomplex };

struct JuliaFractal {
  double c[4] = {1, 0, 0, 0};  // the Julia parameter, (x, y, z, w) = 1, i, j, k parts
  JuliaAlgebra algebra = JuliaAlgebra::kQuaternion;
  int power = 2;                 // 2: sqr, 3: cube
  int max_iteration = 20;        // POV-Ray's default
  double least_step = 1.0 / 20;  // 1 / precision, object units: the march's shortest step
  // The slice hyperplane: a unit 4-vector with slice[3] != 0 and its distance from the origin.
  double slice[4] = {0, 0, 0, 1};
  double slice_distance = 0;
  // POV-Ray's Compute_Fractal_BBox (julia_fractal_set_bounds fills them from c and the algebra).
  double radius = 2, exit_value = 4;
};

// The most iterations accepted (the SDL reader refuses more): the work of one sample is bounded.
constexpr int kJuliaMaxIterations = 100;
// A ray takes at most this many samples and finds at most this many crossings; the rest of its
// chord of the bounding sphere is then left out (no surface there).
constexpr int kJuliaMaxSamples = 1 << 12;
constexpr int kJuliaMaxCrossings = 64;

// radius and exit_value from c and the algebra: quaternion R = min(1 + |c|, 2) (plus POV-Ray's
// 1e-7), exit R^2; hypercomplex R = 4, exit 16.
void julia_fractal_set_bounds(JuliaFractal& julia);

// The bounding sphere's box.
Bounds3d julia_fractal_bounds(const JuliaFractal& julia);

// Whether p's iterates stay within the escape sphere.
bool julia_fractal_contains(const JuliaFractal& julia, Vec3d p);

// The outward normal (not unit) at p near the boundary: the gradient of |z_k(p)|^2 for the first
// iterate k that escapes (or, for a point inside, the largest of those tested).
Vec3d julia_fractal_gradient(const JuliaFractal& julia, Vec3d p);

// Where the ray o + t d crosses the boundary within the bounding sphere's chord [t_in, t_out]:
// whether it starts inside, the crossings' t in increasing order (each the outside end of a
// bisected interval), and whether the march reached t_out; it stops early past `hi`, at the sample
// or crossing cap, with `t_end` where it stopped.
struct JuliaWalk {
  bool inside_at_entry = false;
  bool complete = true;
  int count = 0;
  double crossings[kJuliaMaxCrossings];
  double t_end = 0;
};
// The bounding sphere's chord of the ray; false if it misses.
bool julia_fractal_chord(const JuliaFractal& julia, Vec3d o, Vec3d d, double& t_in, double& t_out);
JuliaWalk julia_fractal_walk(const JuliaFractal& julia, Vec3d o, Vec3d d, double t_in, double t_out,
                             double hi);

}  // namespace fb
