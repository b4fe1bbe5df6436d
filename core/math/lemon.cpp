#include "core/math/lemon.h"

#include <algorithm>
#include <cmath>

namespace fb {

double lemon_widest(const Lemon& lemon) {
  // The profile's rho = sqrt(1 - z^2) - major is largest where |z| is least within the slab.
  const double z = lemon.z_low > 0 ? lemon.z_low : lemon.z_high < 0 ? lemon.z_high : 0;
  return std::sqrt(std::max(1 - z * z, 0.0)) - lemon.major;
}

Bounds3d lemon_bounds(const Lemon& lemon) {
  const double m = lemon_widest(lemon);
  if (!(m > 0) || !(lemon.z_high > lemon.z_low)) return {};
  return {{-m, -m, lemon.z_low}, {m, m, lemon.z_high}};
}

double lemon_value(const Lemon& lemon, Vec3d p) {
  const double rho = std::hypot(p.x, p.y) + lemon.major;
  return rho * rho + p.z * p.z - 1;
}

Vec3d lemon_gradient(const Lemon& lemon, Vec3d p) {
  const double rho = std::hypot(p.x, p.y);
  const double k = rho > 0 ? (rho + lemon.major) / rho : 1;
  return {k * p.x, k * p.y, p.z};
}

void lemon_quartic(const Lemon& lemon, Vec3d o, Vec3d d, double c[5]) {
  const double R2 = lemon.major * lemon.major;
  const double dd = dot(d, d), od = dot(o, d), k = dot(o, o) + R2 - 1;
  c[0] = k * k - 4 * R2 * (o.x * o.x + o.y * o.y);
  c[1] = 4 * od * k - 8 * R2 * (o.x * d.x + o.y * d.y);
  c[2] = 4 * od * od + 2 * dd * k - 4 * R2 * (d.x * d.x + d.y * d.y);
  c[3] = 4 * od * dd;
  c[4] = dd * dd;
}

}  // namespace fb
