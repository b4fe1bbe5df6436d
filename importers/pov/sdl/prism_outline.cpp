#include "importers/pov/sdl/prism_outline.h"

#include <cmath>

namespace fb::pov::sdl {

namespace {

// POV-Ray's test for a repeated point (its EPSILON in prism.cpp): within 1e-10 on each axis.
bool same_prism_point(Vec2d a, Vec2d b) {
  return std::abs(a.x - b.x) < 1e-10 && std::abs(a.y - b.y) < 1e-10;
}

const char* spline_name(PrismSpline spline) {
  switch (spline) {
    case PrismSpline::kLinear:
      return "linear_spline";
    case PrismSpline::kQuadratic:
      return "quadratic_spline";
    case PrismSpline::kCubic:
      return "cubic_spline";
    default:
      return "bezier_spline";
  }
}

}  // namespace

OutlineSegment spline_segment(PrismSpline spline, const Vec2d* p) {
  OutlineSegment s;
  switch (spline) {
    case PrismSpline::kLinear:
      return line_segment(p[0], p[1]);
    case PrismSpline::kQuadratic:
      s.c[0] = p[1];
      s.c[1] = (p[2] - p[0]) * 0.5;
      s.c[2] = p[0] * 0.5 - p[1] + p[2] * 0.5;
      s.degree = 2;
      break;
    default:  // kCubic: Catmull-Rom through p[1], p[2]
      s.c[0] = p[1];
      s.c[1] = (p[2] - p[0]) * 0.5;
      s.c[2] = p[0] - p[1] * 2.5 + p[2] * 2.0 - p[3] * 0.5;
      s.c[3] = p[0] * -0.5 + p[1] * 1.5 - p[2] * 1.5 + p[3] * 0.5;
      s.degree = 3;
  }
  while (s.degree > 1 && s.c[s.degree].x == 0 && s.c[s.degree].y == 0)
    --s.degree;
  s.start = p[1], s.end = p[2];
  return s;
}

std::optional<Outline> prism_outline(PrismSpline spline, const std::vector<Vec2d>& points,
                                     std::vector<std::string>& warnings) {
  const std::string name = spline_name(spline);
  if (points.size() > kMaxPrismPoints)
    throw std::invalid_argument(name + " prism with " + std::to_string(points.size()) +
                                " points, more than the " + std::to_string(kMaxPrismPoints) +
                                " taken");
  const bool bezier = spline == PrismSpline::kBezier;
  // A segment reads `window` points from i; its curve starts at points[i + lead].
  const size_t window = spline == PrismSpline::kLinear      ? 2
                        : spline == PrismSpline::kQuadratic ? 3
                                                            : 4;
  const size_t lead = spline == PrismSpline::kLinear || bezier ? 0 : 1;
  Outline outline;
  size_t first = 0;         // the point the open sub-polygon starts with is points[first + lead]
  size_t loop_segment = 0;  // its first segment in outline.segments
  for (size_t i = 0; i + 1 < points.size();) {
    if (i + window > points.size() && outline.segments.size() > loop_segment) break;  // unclosed
    if (i + window > points.size())
      throw std::invalid_argument(name + " prism: a sub-polygon from point " +
                                  std::to_string(first + 1) + " needs " + std::to_string(window) +
                                  " points for its first segment; " +
                                  std::to_string(points.size() - i) + " are left");
    OutlineSegment s =
        bezier ? cubic_bezier_segment(points[i], points[i + 1], points[i + 2], points[i + 3])
               : spline_segment(spline, &points[i]);
    if (bezier && outline.segments.size() > loop_segment) {
      const Vec2d previous_end = outline.segments.back().end;
      if (!same_prism_point(s.start, previous_end)) {
        warnings.push_back(name + " prism not closed: the segment from point " +
                           std::to_string(i + 1) +
                           " does not start where the one before ends; "
                           "left out, as POV-Ray does");
        return std::nullopt;
      }
      s.c[0] = s.start = previous_end;  // shared bit for bit (core/scene/outline.h)
    }
    const Vec2d loop_start = points[first + lead];
    const bool closes = same_prism_point(s.end, loop_start);
    if (closes) s.end = loop_start;
    if (s.degree > 1 || !same_prism_point(s.start, s.end)) outline.segments.push_back(s);
    if (closes) {
      i += window;
      first = i, loop_segment = outline.segments.size();
    } else {
      i += bezier ? 4 : 1;
    }
  }
  if (outline.segments.size() > loop_segment) {
    if (spline != PrismSpline::kLinear) {
      warnings.push_back(name +
                         " prism not closed: its last sub-polygon does not return to "
                         "point " +
                         std::to_string(first + lead + 1) + "; left out, as POV-Ray does");
      return std::nullopt;
    }
    warnings.push_back(
        "linear_spline prism not closed: closed from its last point back to "
        "point " +
        std::to_string(first + 1) + ", as POV-Ray does");
    outline.segments.push_back(line_segment(outline.segments.back().end, points[first]));
  }
  if (outline.segments.empty())
    throw std::invalid_argument(name + " prism: its " + std::to_string(points.size()) +
                                " points make no curve");
  finish_outline(outline);
  return outline;
}

}  // namespace fb::pov::sdl
