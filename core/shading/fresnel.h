// The Fresnel helpers of Cycles 3.4's closures (kernel/closure/bsdf_util.h).
#pragma once

#include <algorithm>
#include <cmath>

#include <filmback/vec.h>

namespace fb {

// Unpolarised Fresnel reflectance of a dielectric for the cosine `cosi` (either side) and the
// relative index `eta` (Walter et al. 2007, eq. 22, as bsdf_util.h fresnel_dielectric_cos
// writes it); 1 under total internal reflection.
inline float fresnel_dielectric_cos(float cosi, float eta) {
  const float c = std::abs(cosi);
  float g = eta * eta - 1.f + c * c;
  if (!(g > 0.f)) return 1.f;
  g = std::sqrt(g);
  const float A = (g - c) / (g + c);
  const float B = (c * (g + c) - 1.f) / (c * (g - c) + 1.f);
  return 0.5f * A * A * (1.f + B * B);
}

// The refraction of I (unit, on N's side or not) through a surface of relative index `eta` and
// its Fresnel reflectance (bsdf_util.h fresnel_dielectric, from OSL): `inside` is set when I is
// below N, and then N and the index ratio turn round. Returns 1 (and no T) under total internal
// reflection.
inline float fresnel_dielectric(float eta, Vec3f N, Vec3f I, Vec3f& T, bool& inside) {
  float cos_i = dot(N, I), neta;
  Vec3f Nn = N;
  if (cos_i > 0.f) {
    neta = 1.f / eta;
    inside = false;
  } else {
    cos_i = -cos_i;
    neta = eta;
    Nn = -N;
    inside = true;
  }
  const float arg = 1.f - neta * neta * (1.f - cos_i * cos_i);
  if (arg < 0.f) {
    T = {};
    return 1.f;
  }
  const float dnp = std::max(std::sqrt(arg), 1e-7f);
  T = -(neta * I) + (neta * cos_i - dnp) * Nn;
  const float cos_t = -dot(Nn, T);
  const float para = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const float perp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5f * (para * para + perp * perp);
}

// Schlick's weight (1 - u)^5, u clamped to [0, 1] (Schlick 1994; bsdf_util.h schlick_fresnel).
inline float schlick_fresnel(float u) {
  const float m = std::clamp(1.f - u, 0.f, 1.f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

// The Principled BSDF's Fresnel colour (bsdf_util.h interpolate_fresnel_color): the dielectric
// Fresnel at L.H for `ior`, renormalised to run from 0 at normal incidence to 1 at grazing, blends
// the normal-incidence colour cspec0 towards white. F0 is fresnel_dielectric_cos(1, ior).
inline Rgb interpolate_fresnel_color(Vec3f L, Vec3f H, float ior, float F0, Rgb cspec0) {
  const float FH = (fresnel_dielectric_cos(dot(L, H), ior) - F0) / (1.f - F0);
  return cspec0 * (1.f - FH) + Rgb{FH, FH, FH};
}

// Cycles' average(): the mean of the three channels.
inline float average(Rgb c) {
  return (c.x + c.y + c.z) / 3.f;
}

}  // namespace fb
