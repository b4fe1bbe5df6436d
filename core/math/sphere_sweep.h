// POV-Ray's sphere_sweep (POV-Ray 3.7 reference, "Sphere Sweep"; spheresweep.cpp): the union of
// the spheres of centre c(u) and radius r(u) as u runs over each segment of a spline through the
// modelling spheres, c and r interpolated alike: linear (a segment between each two spheres),
// b_spline (uniform cubic B-spline) or cubic_spline (Catmull-Rom), each cubic segment steered by
// four consecutive spheres. A point is inside when some sphere of the sweep holds it:
//   min over u in [0, 1] of |p - c(u)|^2 - r(u)^2 <= 0  for some segment,
// which is POV-Ray's Inside test (the roots of that polynomial in u).
#pragma once

#include <cstdint>
#include <vector>

#include <filmback/vec.h>

#include "core/math/bounds.h"

namespace fb {

enum class SweepSpline : uint8_t { kLinear, kBSpline, kCatmullRom };

// c(u) = c[0] + c[1] u + c[2] u^2 + c[3] u^3 and r(u) likewise, u in [0, 1].
struct SweepSegment {
  Vec3d c[4] = {};
  double r[4] = {0, 0, 0, 0};
  Bounds3d bounds;  // of every sphere of the segment
};

struct SphereSweep {
  std::vector<SweepSegment> segments;
};

// The spheres a spline needs at least: 2 linear, 4 for the cubic splines.
size_t sweep_least_spheres(SweepSpline spline);
// The segments through the modelling spheres (at least sweep_least_spheres of them).
SphereSweep sphere_sweep_from_spheres(SweepSpline spline, const std::vector<Vec3d>& centres,
                                      const std::vector<double>& radii);

Bounds3d sphere_sweep_bounds(const SphereSweep& sweep);

// min over u of |p - c(u)|^2 - r(u)^2 on the segment (< 0: inside it), and the u it is at.
double sweep_segment_value(const SweepSegment& segment, Vec3d p, double* at_u = nullptr);
// The least of that over the segments whose bounds hold p; HUGE_VAL when none does.
double sphere_sweep_value(const SphereSweep& sweep, Vec3d p);
// The outward normal (not unit) at p on the surface of the segment's spheres: from the centre
// of the sphere that touches p.
Vec3d sweep_segment_normal(const SweepSegment& segment, Vec3d p);

// Where the line o + s d may cross the segment's surface: the crossings of its two end spheres
// and the points of the envelope (where the sphere at u touches the line: a polynomial in u of
// degree 2 (linear) or 10 (cubic), whose roots in [0, 1] give s). At most this many:
constexpr int kSweepSegmentCrossings = 14;
int sweep_segment_crossings(const SweepSegment& segment, Vec3d o, Vec3d d, double* s);

}  // namespace fb
