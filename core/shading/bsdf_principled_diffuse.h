// The Principled BSDF's diffuse closure (Cycles 3.4 kernel/closure/bsdf_principled_diffuse.h,
// component PRINCIPLED_DIFFUSE_FULL as svm_closure.h sets it up): Burley 2015, "Extending the
// Disney BRDF to a BSDF with Integrated Subsurface Scattering", section 2.3 — a Lambertian part
// (1 - FL/2)(1 - FV/2) and the retro-reflection RR (FL + FV + FL FV (RR - 1)), RR = roughness
// 2 cos^2(theta_d), all over pi; F = Schlick's weight (1 - cos)^5 of N.L and N.V. Cycles writes
// 2 cos^2(theta_d) as L.V + 1, which needs no half vector. Sampled by the cosine.
#pragma once

#include "core/shading/closure.h"
#include "core/shading/fresnel.h"
#include "core/shading/hemisphere.h"

namespace fb {

inline Rgb principled_diffuse_brdf(const Closure& c, Vec3f V, Vec3f L) {
  const float NdotL = dot(c.N, L);
  if (!(NdotL > 0.f)) return {};
  const float FV = schlick_fresnel(dot(c.N, V)), FL = schlick_fresnel(NdotL);
  const float lambert = (1.f - 0.5f * FV) * (1.f - 0.5f * FL);
  const float RR = c.roughness * (dot(L, V) + 1.f);
  const float value = kInvPi * NdotL * (lambert + RR * (FL + FV + FL * FV * (RR - 1.f)));
  return {value, value, value};
}

inline Rgb principled_diffuse_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in,
                                   float& pdf) {
  if (!(dot(c.N, omega_in) > 0.f)) return pdf = 0.f, Rgb{};
  pdf = dot(c.N, omega_in) * kInvPi;
  return principled_diffuse_brdf(c, ctx.I, omega_in);
}

inline bool principled_diffuse_sample(const Closure& c, const ClosureContext& ctx, Vec2f u,
                                      ClosureSample& s) {
  s.omega_in = sample_cos_hemisphere(c.N, u, s.pdf);
  if (!(dot(ctx.Ng, s.omega_in) > 0.f)) return false;
  s.eval = principled_diffuse_brdf(c, ctx.I, s.omega_in);
  return true;
}

}  // namespace fb
