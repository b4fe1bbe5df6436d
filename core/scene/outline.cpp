#include "core/scene/outline.h"

#include <algorithm>

#include "core/math/polynomial.h"

namespace fb {

namespace {

// One coordinate of a segment as polynomial coefficients.
void coordinate(const OutlineSegment& s, int axis, double out[4]) {
  for (int i = 0; i < 4; ++i)
    out[i] = axis == 0 ? s.c[i].x : s.c[i].y;
}

}  // namespace

OutlineSegment line_segment(Vec2d p0, Vec2d p1) {
  OutlineSegment s;
  s.c[0] = p0, s.c[1] = p1 - p0;
  s.degree = 1;
  s.start = p0, s.end = p1;
  return s;
}

// Bernstein to power form: (1-u)^2 p0 + 2u(1-u) p1 + u^2 p2.
OutlineSegment quadratic_bezier_segment(Vec2d p0, Vec2d p1, Vec2d p2) {
  OutlineSegment s;
  s.c[0] = p0, s.c[1] = (p1 - p0) * 2.0, s.c[2] = p0 - p1 * 2.0 + p2;
  s.degree = 2;
  s.start = p0, s.end = p2;
  return s;
}

// (1-u)^3 p0 + 3u(1-u)^2 p1 + 3u^2(1-u) p2 + u^3 p3.
OutlineSegment cubic_bezier_segment(Vec2d p0, Vec2d p1, Vec2d p2, Vec2d p3) {
  OutlineSegment s;
  s.c[0] = p0;
  s.c[1] = (p1 - p0) * 3.0;
  s.c[2] = (p0 - p1 * 2.0 + p2) * 3.0;
  s.c[3] = p3 - p0 + (p1 - p2) * 3.0;
  s.degree = 3;
  s.start = p0, s.end = p3;
  return s;
}

Vec2d segment_point(const OutlineSegment& s, double u) {
  Vec2d p = s.c[s.degree];
  for (int i = s.degree - 1; i >= 0; --i)
    p = p * u + s.c[i];
  return p;
}

Vec2d segment_tangent(const OutlineSegment& s, double u) {
  Vec2d t = s.c[s.degree] * double(s.degree);
  for (int i = s.degree - 1; i >= 1; --i)
    t = t * u + s.c[i] * double(i);
  return t;
}

void segment_line_polynomial(const OutlineSegment& s, Vec2d origin, Vec2d direction,
                             double coefficients[4]) {
  for (int i = 0; i < 4; ++i) {
    const Vec2d c = i == 0 ? s.c[0] - origin : s.c[i];
    coefficients[i] = c.x * direction.y - c.y * direction.x;
  }
}

void finish_outline(Outline& outline) {
  outline.degrees = 0;
  Vec2d lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (const OutlineSegment& s : outline.segments) {
    outline.degrees += uint32_t(s.degree);
    // The extremes: the ends and where a coordinate's derivative changes sign.
    for (int axis = 0; axis < 2; ++axis) {
      double c[4], dc[3], u[2];
      coordinate(s, axis, c);
      for (int i = 1; i <= s.degree; ++i)
        dc[i - 1] = i * c[i];
      const int count = s.degree > 1 ? sign_changes(dc, s.degree - 1, 0, 1, u) : 0;
      double& l = axis == 0 ? lo.x : lo.y;
      double& h = axis == 0 ? hi.x : hi.y;
      for (double v : {axis == 0 ? s.start.x : s.start.y, axis == 0 ? s.end.x : s.end.y})
        l = std::min(l, v), h = std::max(h, v);
      for (int i = 0; i < count; ++i) {
        const double v = evaluate_polynomial(c, s.degree, u[i]);
        l = std::min(l, v), h = std::max(h, v);
      }
    }
  }
  outline.lo = lo, outline.hi = hi;
}

bool outline_contains(const Outline& outline, Vec2d p) {
  // No crossing right of the box or above or below it. Left of it there may be an odd number when
  // the curves are not closed (a lathe's: core/scene/lathe.h).
  if (!(p.x <= outline.hi.x && p.y >= outline.lo.y && p.y <= outline.hi.y)) return false;
  // Crossings are where "above p" (y > p.y) changes along the closed curves, right of p. Inside
  // a segment the polynomial's sign changes give them. Its value at u = 0 is the exact start
  // (c[0]); at u = 1 it may round to the other side of p.y than the exact end the next segment
  // starts from: that change counts here, at the end, so no crossing is lost or repeated.
  bool inside = false;
  for (const OutlineSegment& s : outline.segments) {
    double c[4], roots[3];
    coordinate(s, 1, c);
    c[0] -= p.y;
    const int count = sign_changes(c, s.degree, 0, 1, roots);
    for (int i = 0; i < count; ++i)
      if (segment_point(s, roots[i]).x > p.x) inside = !inside;
    const bool end_above = s.end.y > p.y;
    if ((evaluate_polynomial(c, s.degree, 1) > 0) != end_above && s.end.x > p.x) inside = !inside;
  }
  return inside;
}

}  // namespace fb
