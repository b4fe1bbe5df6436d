// The shutter curve: how much of the light arriving at each moment of the open interval the
// sensor records. A camera ray's time is drawn from it by inverting its CDF, so the curve weighs
// times by sample density, not by sample weight (Cycles does the same with `shutter_curve`, a
// 256-entry inverted-CDF table; this inverts the piecewise-linear curve exactly).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fb {

class ShutterCurve {
 public:
  ShutterCurve();  // box: every moment of the open interval counts the same
  // "box", "trapezoid[:ramp=R]" (opens over the first R of the interval and closes over the last,
  // 0 <= R <= 0.5, default 0.25) or "table:values=[w0,w1,...]" (at least two non-negative values
  // at evenly spaced times from open to close, linear in between). The plugin-parameter syntax;
  // throws UsageError naming `option`.
  static ShutterCurve parse(std::string_view text, std::string_view option);
  // The table shape from typed values (a scene's sampled curve): 2 to kMaxTableValues values in
  // [0, kMaxTableValue], not all zero. Nothing otherwise; the caller reports kTableExpected,
  // naming where the values came from.
  static std::optional<ShutterCurve> table(std::vector<double> values);
  static constexpr size_t kMaxTableValues = 4096;
  static constexpr double kMaxTableValue = 1e6;
  static constexpr const char* kTableExpected =
      "expected 2 to 4096 values in [0, 1e6], not all zero";

  // The fraction s of the open interval (0 at open, 1 at close) for a sample u in [0, 1):
  // the inverse of cdf().
  double sample(double u) const;
  double cdf(double s) const;  // of the curve normalised to unit area, s in [0, 1]
  const std::string& description() const { return description_; }

 private:
  ShutterCurve(std::vector<double> knots, std::vector<double> values, std::string description);
  std::vector<double> knots_;   // s from 0 to 1, non-decreasing
  std::vector<double> values_;  // the curve at each knot, >= 0
  std::vector<double> area_;    // under the curve from 0 to each knot; area_.back() > 0
  std::string description_;     // for the plan line
};

// Cycles' rolling shutter (kernel/camera/camera.h, camera_sample, rolling_shutter_type TOP): the
// sensor reads its rows from the top down while the shutter is open, each row all at once, and a
// row's rays take their time from that row's window, a share `duration` of the shutter. Cycles
// blends the row's time r and the time s drawn from the shutter curve (fractions of the open
// shutter, 0 at open) by the duration d:
//   s' = 0.5 + d (s - 0.5) + (1 - d) (r - 0.5),  r = (row + 1) / height,
// with rows counted from the top (Cycles counts y from the bottom row: r = 1 - y / height). At
// d = 0 each row is an instant; at d = 1 every row sees the whole shutter (no rolling).
struct RollingShutter {
  double duration = 0;  // in [0, 1]
  static constexpr const char* kExpected = "expected a duration in [0, 1] (a share of the shutter)";
  // s' for a shutter fraction s and film row `row` (0 at the top; rows outside the film, which
  // splatting samples, take the nearest row's time) of an image `height_px` rows high.
  double fraction(double s, double row, uint32_t height_px) const;
  std::string description() const;  // for the plan line
};

}  // namespace fb
