// Axis-aligned boxes in double precision (world or render space), empty until extended.
#pragma once

#include <cmath>

#include <filmback/vec.h>

namespace fb {

struct Bounds3d {
  Vec3d lo{HUGE_VAL, HUGE_VAL, HUGE_VAL};
  Vec3d hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(Vec3d p) { lo = min(lo, p), hi = max(hi, p); }
  void extend(const Bounds3d& b) { lo = min(lo, b.lo), hi = max(hi, b.hi); }
  bool finite() const { return is_finite(lo) && is_finite(hi); }
};

}  // namespace fb
