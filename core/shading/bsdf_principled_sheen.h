// The Principled BSDF's sheen closure (Cycles 3.4 kernel/closure/bsdf_principled_sheen.h;
// Burley 2012, "Physically-Based Shading at Disney", section 5.3): f cos = (1 - L.H)^5 N.L,
// Schlick's weight of the half angle, with no 1/pi (as Cycles writes it). Sampled by the cosine;
// the closure's sample weight is scaled by its value with H = N, (1 - N.I)^5 N.I.
#pragma once

#include "core/shading/closure.h"
#include "core/shading/fresnel.h"
#include "core/shading/hemisphere.h"

namespace fb {

// calculate_avg_principled_sheen_brdf: the factor applied to the sample weight at setup.
inline float principled_sheen_average(Vec3f N, Vec3f I) {
  const float NdotI = dot(N, I);
  return NdotI < 0.f ? 0.f : schlick_fresnel(NdotI) * NdotI;
}

inline Rgb principled_sheen_brdf(Vec3f N, Vec3f V, Vec3f L) {
  const float NdotL = dot(N, L), NdotV = dot(N, V);
  if (NdotL < 0.f || NdotV < 0.f) return {};
  const float value = schlick_fresnel(dot(L, normalize(L + V))) * NdotL;
  return {value, value, value};
}

inline Rgb principled_sheen_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in,
                                 float& pdf) {
  if (!(dot(c.N, omega_in) > 0.f)) return pdf = 0.f, Rgb{};
  pdf = dot(c.N, omega_in) * kInvPi;
  return principled_sheen_brdf(c.N, ctx.I, omega_in);
}

inline bool principled_sheen_sample(const Closure& c, const ClosureContext& ctx, Vec2f u,
                                    ClosureSample& s) {
  s.omega_in = sample_cos_hemisphere(c.N, u, s.pdf);
  if (!(dot(ctx.Ng, s.omega_in) > 0.f)) return false;
  s.eval = principled_sheen_brdf(c.N, ctx.I, s.omega_in);
  return true;
}

}  // namespace fb
