#include "core/math/sor.h"

#include <algorithm>
#include <cmath>

namespace fb {

namespace {

const SorSegment& segment_at(const Sor& sor, double y) {
  for (const SorSegment& s : sor)
    if (y <= s.y1) return s;
  return sor.back();
}

}  // namespace

Sor sor_from_points(const std::vector<std::pair<double, double>>& points) {
  Sor sor;
  for (size_t i = 0; i + 3 < points.size(); ++i) {
    const auto [r_before, y_before] = points[i];
    const auto [r0, y0] = points[i + 1];
    const auto [r1, y1] = points[i + 2];
    const auto [r_after, y_after] = points[i + 3];
    // Hermite interpolation of r^2 in s = (y - y0) / h: values k, slopes m (per unit of y)
    const double h = y1 - y0, k0 = r0 * r0, k1 = r1 * r1;
    const double m0 = 2 * r0 * (r1 - r_before) / (y1 - y_before);
    const double m1 = 2 * r1 * (r_after - r0) / (y_after - y0);
    SorSegment s;
    s.y0 = y0, s.y1 = y1;
    s.c[0] = k0, s.c[1] = h * m0;
    s.c[2] = -3 * k0 - 2 * h * m0 + 3 * k1 - h * m1;
    s.c[3] = 2 * k0 + h * m0 - 2 * k1 + h * m1;
    sor.push_back(s);
  }
  return sor;
}

double sor_radius_2(const SorSegment& s, double y) {
  const double t = (y - s.y0) / (s.y1 - s.y0);
  return s.c[0] + t * (s.c[1] + t * (s.c[2] + t * s.c[3]));
}

Bounds3d sor_bounds(const Sor& sor) {
  double widest_2 = 0;
  for (const SorSegment& s : sor) {
    // r^2 at the ends and where its derivative c1 + 2 c2 t + 3 c3 t^2 vanishes inside
    double at[4] = {0, 1, -1, -1};
    const double a = 3 * s.c[3], b = 2 * s.c[2], c = s.c[1];
    if (a != 0) {
      const double disc = b * b - 4 * a * c;
      if (disc >= 0)
        at[2] = (-b - std::sqrt(disc)) / (2 * a), at[3] = (-b + std::sqrt(disc)) / (2 * a);
    } else if (b != 0) {
      at[2] = -c / b;
    }
    for (double t : at)
      if (t >= 0 && t <= 1)
        widest_2 = std::max(widest_2, sor_radius_2(s, s.y0 + t * (s.y1 - s.y0)));
  }
  const double r = std::sqrt(widest_2);
  return {{-r, sor.front().y0, -r}, {r, sor.back().y1, r}};
}

double sor_value(const Sor& sor, Vec3d p) {
  return p.x * p.x + p.z * p.z - sor_radius_2(segment_at(sor, p.y), p.y);
}

Vec3d sor_side_gradient(const Sor& sor, Vec3d p) {
  const SorSegment& s = segment_at(sor, p.y);
  const double height = s.y1 - s.y0, t = (p.y - s.y0) / height;
  const double slope = (s.c[1] + t * (2 * s.c[2] + t * 3 * s.c[3])) / height;
  return {2 * p.x, -slope, 2 * p.z};
}

}  // namespace fb
