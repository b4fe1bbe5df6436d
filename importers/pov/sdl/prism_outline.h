// POV-Ray's prism points as the curves they draw (POV-Ray 3.7 reference, "Prism"): the
// sub-polygons of a linear, quadratic, cubic or Bézier spline as an Outline (core/scene/outline.h).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/scene/outline.h"

namespace fb::pov::sdl {

enum class PrismSpline { kLinear, kQuadratic, kCubic, kBezier };

// Points past this many are refused: every ray meeting the prism's box solves every segment.
constexpr size_t kMaxPrismPoints = 100'000;

// POV-Ray's linear, quadratic and cubic interpolating splines between p[lead] and p[lead + 1]
// (lead 0 for linear, else 1; cubic reads p[0..3]), in power form: the coefficients of
// Compute_Prism and Compute_Lathe, from the reference's definitions, shared by prism and lathe.
OutlineSegment spline_segment(PrismSpline spline, const Vec2d* p);

// The outline of `points` (<x, z> as written): linear, each point to the next, a sub-polygon
// ending where a point repeats its first; quadratic, a control point then points, ending where
// the first point (after the control) repeats; cubic, the same and one more control point after;
// Bézier, four points a segment, the sub-polygon ending where a segment's end is its first
// segment's start. Throws std::invalid_argument naming the problem when a sub-polygon lacks the
// points of its first segment (or there are too many). An unclosed last linear sub-polygon is
// closed (as POV-Ray does), with a note in `warnings`; any other unclosed outline gives nullopt
// and a warning (POV-Ray leaves the prism out).
std::optional<Outline> prism_outline(PrismSpline spline, const std::vector<Vec2d>& points,
                                     std::vector<std::string>& warnings);

}  // namespace fb::pov::sdl
