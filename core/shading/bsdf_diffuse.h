// Lambert's diffuse closure (Cycles 3.4 kernel/closure/bsdf_diffuse.h, from OSL): f = 1/pi,
// sampled by the cosine. The Diffuse BSDF node with Roughness 0.
#pragma once

#include "core/shading/closure.h"
#include "core/shading/hemisphere.h"

namespace fb {

inline Rgb diffuse_eval(const Closure& c, Vec3f omega_in, float& pdf) {
  const float cos_pi = std::max(dot(c.N, omega_in), 0.f) * kInvPi;
  pdf = cos_pi;
  return {cos_pi, cos_pi, cos_pi};
}

// Directions below the geometric normal are no sample (bsdf_diffuse_sample).
inline bool diffuse_sample(const Closure& c, const ClosureContext& ctx, Vec2f u, ClosureSample& s) {
  s.omega_in = sample_cos_hemisphere(c.N, u, s.pdf);
  if (!(dot(ctx.Ng, s.omega_in) > 0.f)) return false;
  s.eval = {s.pdf, s.pdf, s.pdf};
  return true;
}

}  // namespace fb
