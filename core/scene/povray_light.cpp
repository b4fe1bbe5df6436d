#include "core/scene/povray_light.h"

#include <cmath>

namespace fb {

double povray_fading(const Light& light, double distance_m) {
  if (!(light.fade_power > 0)) return 1;
  if (std::abs(light.fade_distance_m) >= 1e-10)
    return 2 / (1 + std::pow(distance_m / light.fade_distance_m, light.fade_power));
  return std::pow(distance_m, -light.fade_power);
}

double povray_spot_profile(const Light& light, double cos_angle) {
  if (!(cos_angle > 0)) return 0;
  double a = light.spot_tightness != 0 ? std::pow(cos_angle, light.spot_tightness) : 1;
  const double cos_radius = std::cos(light.spot_inner_angle_rad);
  const double cos_falloff = std::cos(light.spot_outer_angle_rad);
  // POV-Ray's cubic_spline(falloff, radius, cos): 0 below the falloff, 1 from the radius on.
  if (cos_radius > 0 && cos_angle < cos_radius) {
    if (cos_angle < cos_falloff) return 0;
    if (cos_radius > cos_falloff) {
      const double t = (cos_angle - cos_falloff) / (cos_radius - cos_falloff);
      a *= (3 - 2 * t) * t * t;
    }
  }
  return a;
}

}  // namespace fb
