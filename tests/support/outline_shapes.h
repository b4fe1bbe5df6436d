// Outlines for the extruded-outline tests: every kind of segment, a hole, and a brute-force
// reference for what the outline encloses.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/scene/outline.h"
#include "core/scene/solid.h"

namespace fb::test {

// A 4 x 4 square with a 1.6 x 1.6 square hole (lines), and beside it a "D": a quadratic arch and
// a cubic bulge closed by a line, so that every degree of segment bounds the set.
inline Outline mixed_outline() {
  Outline o;
  const Vec2d square[4] = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
  const Vec2d hole[4] = {{-0.8, -0.8}, {-0.8, 0.8}, {0.8, 0.8}, {0.8, -0.8}};
  for (int i = 0; i < 4; ++i) {
    o.segments.push_back(line_segment(square[i], square[(i + 1) % 4]));
    o.segments.push_back(line_segment(hole[i], hole[(i + 1) % 4]));
  }
  const Vec2d a{3, -2}, b{6, -1}, c{3, 2};
  o.segments.push_back(quadratic_bezier_segment(a, {5, -3}, b));
  o.segments.push_back(cubic_bezier_segment(b, {7, 0}, {5, 3}, c));
  o.segments.push_back(line_segment(c, a));
  finish_outline(o);
  return o;
}

inline Solid outline_solid(const Outline& outline, const Transform& world_from_object = {}) {
  Solid s;
  s.kind = SolidKind::kOutline;
  s.name = "outline";
  s.outline = std::make_shared<const Outline>(outline);
  s.world_from_object = world_from_object;
  return s;
}

// The outline's curves as polygons of `pieces` chords a segment.
inline std::vector<std::pair<Vec2d, Vec2d>> chords(const Outline& o, int pieces) {
  std::vector<std::pair<Vec2d, Vec2d>> out;
  for (const OutlineSegment& s : o.segments)
    for (int k = 0; k < pieces; ++k)
      out.push_back(
          {segment_point(s, double(k) / pieces), segment_point(s, double(k + 1) / pieces)});
  return out;
}

// Even-odd point in polygon over the chords (the textbook crossing test).
inline bool chords_contain(const std::vector<std::pair<Vec2d, Vec2d>>& chords, Vec2d p) {
  bool inside = false;
  for (const auto& [a, b] : chords)
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (b.x - a.x) * (p.y - a.y) / (b.y - a.y))
      inside = !inside;
  return inside;
}

// Distance from p to the outline's curves: the nearest of many samples, refined by Newton steps
// on |point(u) - p|^2.
inline double distance_to_curves(const Outline& o, Vec2d p) {
  double best = HUGE_VAL;
  for (const OutlineSegment& s : o.segments) {
    double u_best = 0, d_best = HUGE_VAL;
    for (int k = 0; k <= 400; ++k) {
      const Vec2d q = segment_point(s, k / 400.0) - p;
      const double d = std::hypot(q.x, q.y);
      if (d < d_best) d_best = d, u_best = k / 400.0;
    }
    for (int step = 0; step < 30; ++step) {
      const Vec2d q = segment_point(s, u_best) - p, t = segment_tangent(s, u_best);
      const double tt = t.x * t.x + t.y * t.y;
      if (!(tt > 0)) break;
      u_best = std::clamp(u_best - (q.x * t.x + q.y * t.y) / tt, 0.0, 1.0);
    }
    const Vec2d q = segment_point(s, u_best) - p;
    best = std::min({best, d_best, std::hypot(q.x, q.y)});
  }
  return best;
}

}  // namespace fb::test
