// Square root and arc cosine of arguments that rounding can push just outside their domain
// (1 - cos² below 0, a dot product of unit vectors above 1): clamped instead of NaN, as Cycles'
// util/math.h safe_sqrtf and safe_acosf.
#pragma once

#include <algorithm>
#include <cmath>

namespace fb {

inline float safe_sqrt(float x) {
  return std::sqrt(std::max(x, 0.f));
}

inline float safe_acos(float x) {
  return std::acos(std::clamp(x, -1.f, 1.f));
}

}  // namespace fb
