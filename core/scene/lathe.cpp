#include "core/scene/lathe.h"

#include <algorithm>
#include <cmath>

#include "core/math/polynomial.h"

namespace fb {

namespace {

// u is searched this far past [0, 1]: a crossing found by both segments at a joint only splits
// a piece of the ray in two.
constexpr double kLatheJointSlack = 1e-9;

int trimmed_degree(const double* c, int degree) {
  while (degree > 0 && c[degree] == 0)
    --degree;
  return degree;
}

}  // namespace

int lathe_crossings(const OutlineSegment& s, Vec3d o, Vec3d d, double* u, double* t) {
  double roots[kLatheSegmentCrossings];
  if (std::abs(d.y) > kLatheLevelRay * length(d)) {
    // F(u) = |o_xz d.y + (Y(u) - o.y) d_xz|^2 - d.y^2 R(u)^2: the squared distance from the axis
    // less the radius, both times d.y^2, at the ray's point of height Y(u).
    double a[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0}, f[7] = {0, 0, 0, 0, 0, 0, 0};
    for (int k = 0; k <= s.degree; ++k)
      a[k] = d.x * s.c[k].y, b[k] = d.z * s.c[k].y;
    a[0] += o.x * d.y - o.y * d.x;
    b[0] += o.z * d.y - o.y * d.z;
    for (int i = 0; i <= s.degree; ++i)
      for (int j = 0; j <= s.degree; ++j)
        f[i + j] += a[i] * a[j] + b[i] * b[j] - d.y * d.y * s.c[i].x * s.c[j].x;
    const int count = sign_changes(f, trimmed_degree(f, 2 * s.degree), -kLatheJointSlack,
                                   1 + kLatheJointSlack, roots);
    for (int k = 0; k < count; ++k)
      u[k] = roots[k], t[k] = (segment_point(s, roots[k]).y - o.y) / d.y;
    return count;
  }
  // Level: |o_xz + t d_xz|^2 = R(u)^2 where Y(u) = o.y, a quadratic in t for each such u.
  double y[4] = {s.c[0].y - o.y, s.c[1].y, s.c[2].y, s.c[3].y};
  const int heights =
      sign_changes(y, trimmed_degree(y, s.degree), -kLatheJointSlack, 1 + kLatheJointSlack, roots);
  const double qa = d.x * d.x + d.z * d.z, qb = o.x * d.x + o.z * d.z;
  int count = 0;
  for (int k = 0; k < heights && qa > 0; ++k) {
    const double radius = segment_point(s, roots[k]).x;
    const double disc = qb * qb - qa * (o.x * o.x + o.z * o.z - radius * radius);
    if (!(disc > 0)) continue;
    const double root = std::sqrt(disc);
    for (double sign : {-1.0, 1.0})
      u[count] = roots[k], t[count++] = (-qb + sign * root) / qa;
  }
  return count;
}

Bounds3d lathe_bounds(const Outline& profile) {
  const double r = std::max(std::abs(profile.lo.x), std::abs(profile.hi.x));
  return {{-r, profile.lo.y, -r}, {r, profile.hi.y, r}};
}

bool lathe_contains(const Outline& profile, Vec3d p) {
  return outline_contains(profile, {std::hypot(p.x, p.z), p.y});
}

Vec3d lathe_normal(const OutlineSegment& s, Vec3d p, Vec3d d, bool leaving) {
  // The segment's u at p: of the crossings of the same ray through p, the one nearest p.
  double u[kLatheSegmentCrossings], t[kLatheSegmentCrossings];
  const int count = lathe_crossings(s, p, d, u, t);
  double nearest = HUGE_VAL, u_p = 0;
  for (int k = 0; k < count; ++k)
    if (std::abs(t[k]) < nearest) nearest = std::abs(t[k]), u_p = u[k];
  // The profile's tangent turned a quarter, carried to p's meridian (mirrored where R(u) < 0).
  const Vec2d tangent = segment_tangent(s, u_p);
  const double r = std::hypot(p.x, p.z), side = segment_point(s, u_p).x < 0 ? -1 : 1;
  const Vec3d radial = r > 0 ? Vec3d{p.x / r, 0, p.z / r} * side : Vec3d{0, 0, 0};
  Vec3d normal = radial * tangent.y + Vec3d{0, -tangent.x, 0};
  if ((dot(normal, d) > 0) != leaving) normal = -normal;
  return normal;
}

}  // namespace fb
