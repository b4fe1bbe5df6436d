// π, once for the code base, at the two precisions the formulas use: double for set-up and
// geometry, float for shading.
#pragma once

#include <numbers>

namespace fb {

inline constexpr double kPi = std::numbers::pi;
inline constexpr float kPiF = std::numbers::pi_v<float>;

}  // namespace fb
