// A set of closed plane curves made of line, quadratic and cubic segments, whose inside is given
// by the even-odd rule: the cross-section of an extruded outline solid (SolidKind::kOutline),
// which is what POV-Ray's prism and text shapes are (docs/pov.md "Prism and text").
#pragma once

#include <cstdint>
#include <vector>

#include <filmback/vec.h>

namespace fb {

// point(u) = c[0] + c[1] u + c[2] u^2 + c[3] u^3 for u in [0, 1], of degree 1 to 3. `start` and
// `end` are point(0) and point(1) as given, exactly: a contour's segments share them bit for bit,
// so the inside test never sees a gap or an overlap where two segments meet.
struct OutlineSegment {
  Vec2d c[4];
  int degree = 1;
  Vec2d start, end;
};

// Line, quadratic Bézier and cubic Bézier segments in power form.
OutlineSegment line_segment(Vec2d p0, Vec2d p1);
OutlineSegment quadratic_bezier_segment(Vec2d p0, Vec2d p1, Vec2d p2);
OutlineSegment cubic_bezier_segment(Vec2d p0, Vec2d p1, Vec2d p2, Vec2d p3);

Vec2d segment_point(const OutlineSegment& s, double u);
Vec2d segment_tangent(const OutlineSegment& s, double u);  // d point / du, not normalised

// The coefficients of cross(point(u) - origin, direction), a polynomial in u of the segment's
// degree: its sign changes are where the line through `origin` along `direction` crosses it.
void segment_line_polynomial(const OutlineSegment& s, Vec2d origin, Vec2d direction,
                             double coefficients[4]);

struct Outline {
  std::vector<OutlineSegment> segments;  // closed contours, in any order
  Vec2d lo{0, 0}, hi{0, 0};              // the box of every segment (control polygon's hull)
  uint32_t degrees = 0;                  // the sum of the segments' degrees: crossings of a line
};

// Fills outline.lo, hi and degrees from its segments.
void finish_outline(Outline& outline);

// Whether `p` is inside by the even-odd rule: the crossings of the half-line from p towards +x
// (curves that do not close count the same way). Exact at the segments' shared ends (a crossing
// there counts once); on a curve, either answer.
bool outline_contains(const Outline& outline, Vec2d p);

}  // namespace fb
