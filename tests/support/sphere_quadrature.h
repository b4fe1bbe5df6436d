// The unit sphere for tests that integrate over directions: a direction from (cos theta, phi) about
// +z, and the midpoint rule over the sphere in (cos theta, phi), where dω = d(cos theta) dphi.
#pragma once

#include <algorithm>
#include <cmath>

#include <filmback/vec.h>

#include "core/math/constants.h"

namespace fb::test {

inline Vec3f direction(double cos_theta, double phi) {
  const double s = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  return Vec3f(Vec3d{s * std::cos(phi), s * std::sin(phi), cos_theta});
}

// The integral of g(ω) over the sphere with n × n midpoints: a lobe of GGX alpha α needs n of
// about 100 / α to resolve its peak.
template <typename G>
double sphere_integral(int n, G g) {
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double c = -1 + (i + 0.5) * 2.0 / n;
    for (int j = 0; j < n; ++j)
      sum += g(direction(c, (j + 0.5) * 2 * kPi / n));
  }
  return sum * (2.0 / n) * (2 * kPi / n);
}

}  // namespace fb::test
