// Oren-Nayar rough diffuse closure in Fujii's "qualitative" form (Yasuhiro Fujii, "A tiny
// improvement of Oren-Nayar reflectance model"; Cycles 3.4 kernel/closure/bsdf_oren_nayar.h):
// f = A + B s / t with s = L.V - (N.L)(N.V), t = max(N.L, N.V) where s > 0, A = 1 / (pi +
// (3 pi - 4) sigma / 6), B = sigma A. The Diffuse BSDF node with Roughness sigma > 0. Cycles
// samples it uniformly over the hemisphere.
#pragma once

#include <algorithm>
#include <cfloat>
#include <numbers>

#include "core/shading/closure.h"
#include "core/shading/hemisphere.h"

namespace fb {

inline void oren_nayar_setup(Closure& c, float sigma) {
  sigma = std::clamp(sigma, 0.f, 1.f);
  constexpr float kPi = std::numbers::pi_v<float>;
  const float div = 1.f / (kPi + ((3.f * kPi - 4.f) / 6.f) * sigma);
  c.type = ClosureType::kOrenNayar;
  c.oren_nayar = {div, sigma * div};
}

inline Rgb oren_nayar_intensity(const Closure& c, Vec3f V, Vec3f L) {
  const float nl = std::max(dot(c.N, L), 0.f), nv = std::max(dot(c.N, V), 0.f);
  float t = dot(L, V) - nl * nv;
  if (t > 0.f) t /= std::max(nl, nv) + FLT_MIN;
  const float is = nl * (c.oren_nayar.a + c.oren_nayar.b * t);
  return {is, is, is};
}

inline Rgb oren_nayar_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in,
                           float& pdf) {
  if (!(dot(c.N, omega_in) > 0.f)) return pdf = 0.f, Rgb{};
  pdf = 0.5f * kInvPi;
  return oren_nayar_intensity(c, ctx.I, omega_in);
}

inline bool oren_nayar_sample(const Closure& c, const ClosureContext& ctx, Vec2f u,
                              ClosureSample& s) {
  s.omega_in = sample_uniform_hemisphere(c.N, u, s.pdf);
  if (!(dot(ctx.Ng, s.omega_in) > 0.f)) return false;
  s.eval = oren_nayar_intensity(c, ctx.I, s.omega_in);
  return true;
}

}  // namespace fb
