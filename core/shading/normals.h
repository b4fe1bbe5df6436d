// What Cycles does to shading normals before its closures see them (Blender's renders apply both
// to every surface): the mirror direction kept above the true surface, and the shadowing of
// diffuse light where a bump or normal map bent the normal away from the interpolated one.
#pragma once

#include <algorithm>
#include <cmath>

#include <filmback/vec.h>

namespace fb {

// Chiang, Li and Burley 2019, "Taming the Shadow Terminator": light from `wi` reaching a diffuse
// surface whose shading normal `n` was bent away from the interpolated `smooth` normal is
// shadowed by g = (smooth.wi) / ((n.wi)(smooth.n)), smoothed as -g^3 + g^2 + g, with `smooth`
// turned to wi's side of n (Cycles' bump_shadowing_term, kernel/closure/bsdf.h, which Cycles
// applies to every diffuse closure whose normal is not the smooth one).
inline float bump_shadowing_term(Vec3f smooth, Vec3f n, Vec3f wi) {
  const float cos_ni = dot(n, wi);
  if (cos_ni < 0.f) smooth = -smooth;
  const float denominator = cos_ni * dot(smooth, n);
  const float g = denominator != 0.f ? dot(smooth, wi) / denominator : 0.f;  // safe_divide
  if (g >= 1.f) return 1.f;
  if (!(g >= 0.f)) return 0.f;
  return g + g * g - g * g * g;
}

// The same in a local frame whose shading normal is +z.
inline float bump_shadowing(Vec3f smooth, Vec3f wi) {
  return bump_shadowing_term(smooth, {0.f, 0.f, 1.f}, wi);
}

// A shading normal that a ray seen from `wo` (unit, towards the viewer, on ng's side) can reflect
// about without the mirror direction dipping below the true surface: `ns` unchanged when it is
// fine, else turned towards `ng` just enough (Cycles' ensure_valid_reflection, kernel/closure/
// bsdf_util.h, which Blender's renders apply to every shading normal). Normal maps and
// interpolated normals otherwise turn away from a grazing viewer, and such points render black.
inline Vec3f ensure_valid_reflection(Vec3f ng, Vec3f wo, Vec3f ns) {
  const Vec3f r = ns * (2.f * dot(ns, wo)) - wo;
  // Reflections may always be at least as shallow as the incoming ray.
  const float threshold = std::min(0.9f * dot(ng, wo), 0.01f);
  if (dot(ng, r) >= threshold) return ns;
  // In the plane of ng (z) and ns (x): the normal whose mirror direction has height `threshold`.
  const Vec3f x0 = ns - ng * dot(ns, ng);
  const float x_len = length(x0);
  if (!(x_len > 0.f)) return ng;
  const Vec3f x = x0 / x_len;
  const float ix = dot(wo, x), iz = dot(wo, ng);
  const float a = ix * ix + iz * iz;
  const float b = std::sqrt(std::max(0.f, ix * ix * (a - threshold * threshold)));
  const float c = iz * threshold + a;
  const float n1_z2 = 0.5f / a * (b + c), n2_z2 = 0.5f / a * (c - b);
  bool valid1 = n1_z2 > 1e-5f && n1_z2 <= 1.f + 1e-5f;
  bool valid2 = n2_z2 > 1e-5f && n2_z2 <= 1.f + 1e-5f;
  const auto normal = [](float z2) {
    return Vec2f{std::sqrt(std::max(0.f, 1.f - z2)), std::sqrt(std::max(0.f, z2))};
  };
  Vec2f n;
  if (valid1 && valid2) {
    // Both reach the threshold: prefer the one whose reflection is lower but above it.
    const Vec2f n1 = normal(n1_z2), n2 = normal(n2_z2);
    const float r1 = 2.f * (n1.x * ix + n1.y * iz) * n1.y - iz;
    const float r2 = 2.f * (n2.x * ix + n2.y * iz) * n2.y - iz;
    valid1 = r1 >= 1e-5f, valid2 = r2 >= 1e-5f;
    n = valid1 && valid2 ? (r1 < r2 ? n1 : n2) : (r1 > r2 ? n1 : n2);
  } else if (valid1 || valid2) {
    n = normal(valid1 ? n1_z2 : n2_z2);
  } else {
    return ng;
  }
  return x * n.x + ng * n.y;
}

}  // namespace fb
