// lathe { [linear_spline | quadratic_spline | cubic_spline | bezier_spline] N, <r1, y1>, ...
// [sturm] } (POV-Ray 3.7 reference, "Lathe"): the points' curve in the (radius, height) plane,
// turned about the y axis. Its segments are POV-Ray's splines (importers/pov/sdl/prism_outline.h)
// over consecutive points, as Compute_Lathe makes them: the curve need not close.
#include "core/util/error.h"
#include "importers/pov/sdl/parser.h"
#include "importers/pov/sdl/prism_outline.h"

namespace fb::pov::sdl {

namespace {

struct LatheKeyword {
  std::string_view name;
  PrismSpline spline;
  size_t least_points;  // POV-Ray's Parse_Lathe: one segment's worth
};

constexpr LatheKeyword kLatheSplines[] = {{"linear_spline", PrismSpline::kLinear, 2},
                                          {"quadratic_spline", PrismSpline::kQuadratic, 3},
                                          {"cubic_spline", PrismSpline::kCubic, 4},
                                          {"bezier_spline", PrismSpline::kBezier, 4}};

// The segments: linear from each point to the next; quadratic and cubic between the points after
// the first (the first, and the cubic's last, steer the end slopes); Bézier four points a segment.
Outline lathe_profile(PrismSpline spline, const std::vector<Vec2d>& points) {
  Outline profile;
  const bool bezier = spline == PrismSpline::kBezier;
  const size_t window = spline == PrismSpline::kLinear      ? 2
                        : spline == PrismSpline::kQuadratic ? 3
                                                            : 4;
  for (size_t i = 0; i + window <= points.size(); i += bezier ? 4 : 1) {
    // Consecutive splines share their end point bit for bit (core/scene/outline.h): it is the
    // same point read once.
    profile.segments.push_back(
        bezier ? cubic_bezier_segment(points[i], points[i + 1], points[i + 2], points[i + 3])
               : spline_segment(spline, &points[i]));
  }
  finish_outline(profile);
  return profile;
}

}  // namespace

void Parser::parse_lathe(Object& o) {
  o.shape = Shape::kLathe;
  const LatheKeyword* kind = &kLatheSplines[0];
  for (const LatheKeyword& k : kLatheSplines)
    if (peek().word(k.name)) {
      kind = &k;
      next();
    }
  const double n = parse_count();
  const SourceLocation count_at = here();
  if (!(n >= double(kind->least_points) && n <= double(options().limits.objects)))
    fail_at(count_at, std::string(kind->name) + " lathe needs at least " +
                          std::to_string(kind->least_points) + " points, got " + number_string(n));
  if (kind->spline == PrismSpline::kBezier && size_t(n) % 4 != 0)
    fail_at(count_at, "bezier_spline lathe needs four points a segment, got " + number_string(n));
  count_objects(uint64_t(n));
  std::vector<Vec2d> points;
  for (size_t i = 0; i < size_t(n); ++i) {
    accept(",");
    const SourceLocation where = location_of(peek());
    const Value v = parse_numeric(2);
    if (!std::isfinite(v.v[0]) || !std::isfinite(v.v[1]))
      fail_at(where, "lathe point is not finite");
    // POV-Ray's "Incorrect point in lathe": the curve's inner points may not cross the axis.
    if (i > 0 && i + 1 < size_t(n) && v.v[0] < 0)
      fail_at(where, "lathe point's radius " + number_string(v.v[0]) + " is negative");
    points.push_back({v.v[0], v.v[1]});
  }
  o.outline = std::make_shared<const Outline>(lathe_profile(kind->spline, points));
}

}  // namespace fb::pov::sdl
