// Small double-precision helpers shared by the code that cuts and joins meshes
// (core/tessellate/csg_trim.cpp, core/tessellate/seam_join.cpp).
#pragma once

#include <algorithm>
#include <cmath>

#include <filmback/vec.h>

namespace fb {

// v made unit length, or `fallback` when v has no length.
inline Vec3d unit_or(Vec3d v, Vec3d fallback) {
  const double len = length(v);
  return len > 0 ? v / len : fallback;
}

// The parameter in [0, 1] of the point of segment [a, b] nearest p.
inline double segment_parameter(Vec3d p, Vec3d a, Vec3d b) {
  const Vec3d ab = b - a;
  const double len2 = dot(ab, ab);
  return len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
}

inline double distance_to_segment(Vec3d p, Vec3d a, Vec3d b) {
  return length(p - (a + (b - a) * segment_parameter(p, a, b)));
}

}  // namespace fb
