// POV-Ray's lathe (SolidKind::kLathe): an Outline's curves in the (radius, height) = (x, y) plane
// turned about the y axis. What the intersector and the tessellator need of it: where a ray
// crosses the surface a segment turns, the inside test, the surface's normal.
#pragma once

#include <filmback/vec.h>

#include "core/math/bounds.h"
#include "core/scene/outline.h"

namespace fb {

// A ray crosses the surface one segment turns at most this often (2 x its degree, 3 at most).
constexpr int kLatheSegmentCrossings = 6;

// Rays closer to level than this (|d.y| / |d|) are solved as level: the polynomial in u that
// the others solve degenerates there (its roots pair up).
constexpr double kLatheLevelRay = 1e-9;

// Where the ray o + t d crosses the surface segment s turns, at the segment's u (searched a
// little past [0, 1], so that a ray through two segments' joint meets at least one of them) and
// the ray's t; returns how many (at most kLatheSegmentCrossings). The degree is twice the
// segment's, as POV-Ray's (6 for cubic and Bézier splines): at the curve's height Y(u) the ray
// is at t = (Y(u) - o.y) / d.y, where its squared distance from the axis is R(u)^2. A level ray
// meets the circles of radius R(u) where Y(u) is its height.
int lathe_crossings(const OutlineSegment& s, Vec3d o, Vec3d d, double* u, double* t);

// The profile's box turned about y.
Bounds3d lathe_bounds(const Outline& profile);

// Inside by POV-Ray's rule (Lathe::Inside): the half-line from (sqrt(x^2 + z^2), y) towards +x
// crosses the curves an odd number of times.
bool lathe_contains(const Outline& profile, Vec3d p);

// The surface's normal (not normalised) at p on the surface segment s turns, facing the side
// the ray along d comes from when `leaving` is false, else the side it goes to.
Vec3d lathe_normal(const OutlineSegment& s, Vec3d p, Vec3d d, bool leaving);

}  // namespace fb
