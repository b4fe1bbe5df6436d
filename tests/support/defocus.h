// The thin lens's circle of confusion (docs/camera-model.md, "The lens: pinhole or thin lens"), for
// the tests that measure defocus blur.
#pragma once

#include <cmath>

namespace fb::test {

// The blur diameter on the sensor, mm, of a point at depth_m seen through a lens of focal length
// focal_mm and f-number fstop focused at focus_m (HUGE_VAL: at infinity). Blender's thin lens
// keeps the image distance at f, so its own focal length is f' = f D_f / (D_f + f) and
// c = A |D - D_f| / D * f' / (D_f - f') with A = f / N; at infinite focus this tends to A f / D.
inline double circle_of_confusion_mm(double focal_mm, double fstop, double focus_m,
                                     double depth_m) {
  const double f = focal_mm * 1e-3, aperture_mm = focal_mm / fstop;
  if (std::isinf(focus_m)) return aperture_mm * f / depth_m;
  const double lens = f * focus_m / (focus_m + f);
  return aperture_mm * std::abs(depth_m - focus_m) / depth_m * lens / (focus_m - lens);
}

}  // namespace fb::test
