// Geometric helpers that plugins need around surface hits.
#pragma once

#include <cmath>

#include "plugin_abi.h"
#include "vec.h"

namespace fb {

// Right-handed orthonormal basis around a unit normal (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited"), so local (x, y, z) maps to tangent, bitangent, normal.
struct Frame {
  Vec3f s, t, n;
  explicit Frame(Vec3f normal) : n(normal) {
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = {1.f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = {b, sign + n.y * n.y * a, -n.y};
  }
  Vec3f to_world(Vec3f v) const { return s * v.x + t * v.y + n * v.z; }
  Vec3f to_local(Vec3f v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

// Moves a ray origin off a surface by just enough to clear the floating-point error of the hit
// point, on the side `w` leaves towards (pbrt 4e §6.8.6): no scene-dependent epsilon.
inline Vec3f offset_ray_origin(Vec3f p, Vec3f p_error, Vec3f n, Vec3f w) {
  const float d = dot(abs(n), p_error);
  Vec3f offset = n * d;
  if (dot(w, n) < 0.f) offset = -offset;
  Vec3f po = p + offset;
  auto away = [](float v, float dir) {
    if (dir > 0.f) return std::nextafter(v, INFINITY);
    if (dir < 0.f) return std::nextafter(v, -INFINITY);
    return v;
  };
  return {away(po.x, offset.x), away(po.y, offset.y), away(po.z, offset.z)};
}

// The shadow ray from `origin` towards a sampled light in `direction`, `light_distance` away
// (infinite for a distant light): it stops a relative 1e-4 short of the light, so that it does not
// meet the light's own surface.
inline fb_ray shadow_ray_to_light(Vec3f origin, const float direction[3], float light_distance,
                                  float time_s) {
  fb_ray ray{};
  origin.store(ray.origin);
  for (int c = 0; c < 3; ++c)
    ray.direction[c] = direction[c];
  ray.t_max = std::isinf(light_distance) ? HUGE_VALF : light_distance * (1.f - 1e-4f);
  ray.time_s = time_s;
  return ray;
}

}  // namespace fb
