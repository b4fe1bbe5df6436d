#include "core/scene/isosurface.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fb {

Bounds3d isosurface_bounds(const Isosurface& iso) {
  if (!iso.sphere_container) return {min(iso.box_lo, iso.box_hi), max(iso.box_lo, iso.box_hi)};
  const Vec3d r{iso.radius, iso.radius, iso.radius};
  return {iso.centre - r, iso.centre + r};
}

bool isosurface_container_chord(const Isosurface& iso, Vec3d o, Vec3d d, double& t_in,
                                double& t_out) {
  if (iso.sphere_container) {
    // |o - c + t d|^2 = r^2, solved about the point nearest the centre for precision
    const double a = dot(d, d);
    if (!(a > 0)) return false;
    const Vec3d oc = o - iso.centre;
    const double t0 = -dot(oc, d) / a;
    const Vec3d nearest = oc + d * t0;
    const double h2 = (iso.radius * iso.radius - dot(nearest, nearest)) / a;
    if (!(h2 > 0)) return false;
    const double h = std::sqrt(h2);
    t_in = t0 - h, t_out = t0 + h;
    return true;
  }
  const Bounds3d box = isosurface_bounds(iso);
  t_in = -HUGE_VAL, t_out = HUGE_VAL;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < box.lo[a] || o[a] > box.hi[a]) return false;
      continue;
    }
    double t1 = (box.lo[a] - o[a]) / d[a], t2 = (box.hi[a] - o[a]) / d[a];
    if (t1 > t2) std::swap(t1, t2);
    t_in = std::max(t_in, t1), t_out = std::min(t_out, t2);
  }
  return t_in < t_out && std::isfinite(t_in) && std::isfinite(t_out);
}

bool isosurface_container_holds(const Isosurface& iso, Vec3d p) {
  if (iso.sphere_container) {
    const Vec3d from_centre = p - iso.centre;
    return dot(from_centre, from_centre) <= iso.radius * iso.radius;
  }
  const Bounds3d box = isosurface_bounds(iso);
  for (int a = 0; a < 3; ++a)
    if (!(p[a] >= box.lo[a] && p[a] <= box.hi[a])) return false;
  return true;
}

Vec3d isosurface_container_normal(const Isosurface& iso, Vec3d p) {
  if (iso.sphere_container) return p - iso.centre;
  // The face p is nearest to.
  const Bounds3d box = isosurface_bounds(iso);
  double n[3] = {0, 0, 0}, nearest = HUGE_VAL;
  for (int a = 0; a < 3; ++a)
    for (const auto& [distance, sign] :
         {std::pair{std::abs(p[a] - box.lo[a]), -1.0}, {std::abs(box.hi[a] - p[a]), 1.0}})
      if (distance < nearest) {
        nearest = distance;
        n[0] = n[1] = n[2] = 0;
        n[a] = sign;
      }
  return {n[0], n[1], n[2]};
}

}  // namespace fb
