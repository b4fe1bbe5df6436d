#include "core/shading/bsdf_microfacet.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/math/constants.h"
#include "core/math/safe_math.h"
#include "core/shading/fresnel.h"
#include "core/shading/hemisphere.h"

namespace fb {
namespace {

// Giles 2010, "Approximating the erfinv function" (GPU Computing Gems), single precision: the
// inverse error function Cycles' fast_ierff approximates the same way.
float erf_inverse(float x) {
  float w = -std::log(std::max((1.f - x) * (1.f + x), 1e-30f)), p;
  if (w < 5.f) {
    w -= 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = std::sqrt(w) - 3.f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  return p * x;
}

// Slopes of the visible normals of the unit-roughness Beckmann distribution seen at
// theta_i (Jakob 2014, with its two Newton steps), and G1 for that direction.
Vec2f beckmann_slopes(float cos_i, float sin_i, Vec2f u, float& G1) {
  if (cos_i >= 0.99999f) {
    const float r = std::sqrt(-std::log(std::max(u.x, 1e-30f))), phi = 2.f * kPiF * u.y;
    G1 = 1.f;
    return {r * std::cos(phi), r * std::sin(phi)};
  }
  const float tan_i = sin_i / cos_i, cot_i = 1.f / tan_i;
  const float erf_a = std::erf(cot_i), exp_a2 = std::exp(-cot_i * cot_i);
  constexpr float kSqrtPiInv = 0.56418958354f;
  const float lambda = 0.5f * (erf_a - 1.f) + 0.5f * kSqrtPiInv * exp_a2 * tan_i;
  G1 = 1.f / (1.f + lambda);
  const float K = tan_i * kSqrtPiInv;
  const float y_approx = u.x * (1.f + erf_a + K * (1.f - erf_a * erf_a));
  const float y_exact = u.x * (1.f + erf_a + K * exp_a2);
  float b = K > 0.f ? (0.5f - std::sqrt(K * (K - y_approx + 1.f) + 0.25f)) / K : y_approx - 1.f;
  float inv_erf = erf_inverse(b);
  float value = 1.f + b + K * std::exp(-inv_erf * inv_erf) - y_exact;
  float slope_x = inv_erf;
  if (std::abs(value) > 1e-6f) {
    b -= value / (1.f - inv_erf * tan_i);
    inv_erf = erf_inverse(b);
    value = 1.f + b + K * std::exp(-inv_erf * inv_erf) - y_exact;
    b -= value / (1.f - inv_erf * tan_i);
    slope_x = erf_inverse(b);
  }
  return {slope_x, erf_inverse(2.f * u.y - 1.f)};
}

// Heitz and d'Eon 2014, appendix: slopes of the visible normals of the unit-roughness GGX
// distribution, and G1.
Vec2f ggx_slopes(float cos_i, float sin_i, Vec2f u, float& G1) {
  if (cos_i >= 0.99999f) {
    const float r = std::sqrt(u.x / (1.f - u.x)), phi = 2.f * kPiF * u.y;
    G1 = 1.f;
    return {r * std::cos(phi), r * std::sin(phi)};
  }
  const float tan_i = sin_i / cos_i;
  const float G1_inv = 0.5f * (1.f + safe_sqrt(1.f + tan_i * tan_i));
  G1 = 1.f / G1_inv;
  const float A = 2.f * u.x * G1_inv - 1.f, AA = A * A;
  const float tmp = 1.f / (AA - 1.f);
  const float B = tan_i, BB = B * B;
  const float D = safe_sqrt(BB * tmp * tmp - (AA - BB) * tmp);
  const float slope_x1 = B * tmp - D, slope_x2 = B * tmp + D;
  const float slope_x = (A < 0.f || slope_x2 * tan_i > 1.f) ? slope_x1 : slope_x2;
  float S, v = u.y;
  if (v > 0.5f) {
    S = 1.f, v = 2.f * (v - 0.5f);
  } else {
    S = -1.f, v = 2.f * (0.5f - v);
  }
  // The y slope, scaled by sqrt(1 + slope_x^2), has the CDF 2/pi (z/(1 + z^2) + atan z) on
  // z >= 0. Heitz and d'Eon's rational fit of its inverse (Cycles' sampler) is off by up to
  // 7.6e-4 in probability, enough for a chi-square test of 3e5 samples to see; two Newton steps
  // from it solve the CDF to float precision, so that the samples follow the pdf eval() reports.
  float z = (v * (v * (v * 0.27385f - 0.73369f) + 0.46341f)) /
            (v * (v * (v * 0.093073f + 0.309420f) - 1.f) + 0.597999f);
  for (int i = 0; i < 2; ++i) {
    const float z2 = 1.f + z * z;
    const float cdf = (z / z2 + std::atan(z)) * (2.f / kPiF);
    const float density = 4.f / (kPiF * z2 * z2);
    z = std::max(0.f, z - (cdf - v) / density);
  }
  return {slope_x, S * z * safe_sqrt(1.f + slope_x * slope_x)};
}

// microfacet_sample_stretched: stretch I to unit roughness, sample slopes, rotate, unstretch.
Vec3f sample_stretched(Vec3f I, float alpha_x, float alpha_y, Vec2f u, bool beckmann, float& G1) {
  const Vec3f s = normalize(Vec3f{alpha_x * I.x, alpha_y * I.y, I.z});
  float cos_t = 1.f, sin_t = 0.f, cos_p = 1.f, sin_p = 0.f;
  if (s.z < 0.99999f) {
    cos_t = s.z;
    sin_t = safe_sqrt(1.f - cos_t * cos_t);
    cos_p = s.x / sin_t;
    sin_p = s.y / sin_t;
  }
  Vec2f slope = beckmann ? beckmann_slopes(cos_t, sin_t, u, G1) : ggx_slopes(cos_t, sin_t, u, G1);
  slope = {cos_p * slope.x - sin_p * slope.y, sin_p * slope.x + cos_p * slope.y};
  return normalize(Vec3f{-alpha_x * slope.x, -alpha_y * slope.y, 1.f});
}

// Smith's G1 for GGX with the squared (projected) roughness alpha2 (Walter eq. 34).
float ggx_G1(float alpha2, float cos_n) {
  return 2.f / (1.f + safe_sqrt(1.f + alpha2 * (1.f - cos_n * cos_n) / (cos_n * cos_n)));
}

// Walter eq. 27: Beckmann's G1 as a rational function of a = 1 / (alpha tan).
float beckmann_G1_of(float inv_a) {
  if (inv_a < 0.625f) return 1.f;
  const float a = 1.f / inv_a;
  return ((2.181f * a + 3.535f) * a) / ((2.577f * a + 2.276f) * a + 1.f);
}
float beckmann_G1(float alpha, float cos_n) {
  const float c2 = cos_n * cos_n;
  return beckmann_G1_of(alpha * safe_sqrt((1.f - c2) / c2));
}
// The anisotropic form: the roughness projected on w's azimuth.
float projected_alpha2(float alpha_x, float alpha_y, float cos_phi, float sin_phi) {
  const float c2 = cos_phi * cos_phi, s2 = sin_phi * sin_phi;
  return (c2 * alpha_x * alpha_x + s2 * alpha_y * alpha_y) / (c2 + s2);
}
float beckmann_aniso_G1(float alpha_x, float alpha_y, float cos_n, float cos_phi, float sin_phi) {
  const float c2 = cos_n * cos_n;
  return beckmann_G1_of(
      safe_sqrt(projected_alpha2(alpha_x, alpha_y, cos_phi, sin_phi) * (1.f - c2) / c2));
}

float ggx_D(float alpha2, float cos_m) {
  const float c2 = cos_m * cos_m, tan2 = (1.f - c2) / c2;
  return alpha2 / (kPiF * c2 * c2 * (alpha2 + tan2) * (alpha2 + tan2));
}
float beckmann_D(float alpha2, float cos_m) {
  const float c2 = cos_m * cos_m, tan2 = (1.f - c2) / c2;
  return std::exp(-tan2 / alpha2) / (kPiF * alpha2 * c2 * c2);
}
// Anisotropic D from the microfacet's slopes in the tangent frame.
float aniso_D(const MicrofacetParams& p, Vec3f local_m) {
  const float sx = -local_m.x / (local_m.z * p.alpha_x), sy = -local_m.y / (local_m.z * p.alpha_y);
  const float c4 = local_m.z * local_m.z * local_m.z * local_m.z;
  const float norm = kPiF * p.alpha_x * p.alpha_y * c4;
  if (p.distribution == MicrofacetDistribution::kBeckmann)
    return std::exp(-sx * sx - sy * sy) / norm;
  const float len = 1.f + sx * sx + sy * sy;
  return 1.f / (len * len * norm);
}

// Burley 2012's GTR1 (the clearcoat's "generalized Trowbridge-Reitz" with gamma = 1).
float gtr1_D(float cos_m, float alpha) {
  if (alpha >= 1.f) return kInvPi;
  const float a2 = alpha * alpha, t = 1.f + (a2 - 1.f) * cos_m * cos_m;
  return (a2 - 1.f) / (kPiF * std::log(a2) * t);
}

// reflection_color plus the clearcoat's 0.25 clearcoat factor.
Rgb fresnel_color(const MicrofacetParams& p, Vec3f L, Vec3f H) {
  Rgb F{1.f, 1.f, 1.f};
  if (p.fresnel != FresnelMode::kNone)
    F = interpolate_fresnel_color(L, H, p.ior, fresnel_dielectric_cos(1.f, p.ior), p.cspec0);
  if (p.fresnel == FresnelMode::kClearcoat) F *= 0.25f * p.clearcoat;
  return F;
}

bool isotropic(const MicrofacetParams& p) {
  return p.alpha_x == p.alpha_y;
}

Rgb eval_reflect(const Closure& c, Vec3f I, Vec3f omega_in, float cosNO, float cosNI, float& pdf) {
  const MicrofacetParams& p = c.microfacet;
  if (!(cosNI > 0.f && cosNO > 0.f)) return pdf = 0.f, Rgb{};
  const Vec3f m = normalize(omega_in + I);
  const bool beckmann = p.distribution == MicrofacetDistribution::kBeckmann;
  float alpha2 = p.alpha_x * p.alpha_y, D, G1o, G1i;
  if (isotropic(p)) {
    const float cos_m = dot(c.N, m);
    if (p.fresnel == FresnelMode::kClearcoat) {
      D = gtr1_D(cos_m, p.alpha_x);
      alpha2 = 0.0625f;  // the clearcoat's masking is GGX at a fixed alpha 0.25
    } else {
      D = beckmann ? beckmann_D(alpha2, cos_m) : ggx_D(alpha2, cos_m);
    }
    G1o = beckmann ? beckmann_G1(p.alpha_x, cosNO) : ggx_G1(alpha2, cosNO);
    G1i = beckmann ? beckmann_G1(p.alpha_x, cosNI) : ggx_G1(alpha2, cosNI);
  } else {
    const TangentFrame f(c.N, p.T);
    D = aniso_D(p, f.to_local(m));
    const Vec3f lo = f.to_local(I), li = f.to_local(omega_in);
    if (beckmann) {
      G1o = beckmann_aniso_G1(p.alpha_x, p.alpha_y, cosNO, lo.x, lo.y);
      G1i = beckmann_aniso_G1(p.alpha_x, p.alpha_y, cosNI, li.x, li.y);
    } else {
      G1o = ggx_G1(projected_alpha2(p.alpha_x, p.alpha_y, lo.x, lo.y), cosNO);
      G1i = ggx_G1(projected_alpha2(p.alpha_x, p.alpha_y, li.x, li.y), cosNI);
    }
  }
  // Walter eq. 20 times cos(omega_in): F G D / (4 cosNO); the visible-normal pdf with the
  // reflection Jacobian 1 / (4 m.I) is G1o D / (4 cosNO) (Heitz and d'Eon eq. 2, Walter eq. 38).
  const float common = D * 0.25f / cosNO;
  pdf = G1o * common;
  return fresnel_color(p, omega_in, m) * (G1o * G1i * common);
}

Rgb eval_transmit(const Closure& c, Vec3f I, Vec3f omega_in, float cosNO, float cosNI, float& pdf) {
  const MicrofacetParams& p = c.microfacet;
  if (cosNO <= 0.f || cosNI >= 0.f) return pdf = 0.f, Rgb{};
  const float eta = p.ior;
  // Walter eq. 16; the sign of the half vector does not matter below.
  const Vec3f ht = -(eta * omega_in + I);
  const Vec3f Ht = normalize(ht);
  const float cosHO = dot(Ht, I), cosHI = dot(Ht, omega_in);
  const float alpha2 = p.alpha_x * p.alpha_y;
  const bool beckmann = p.distribution == MicrofacetDistribution::kBeckmann;
  float D, G;
  if (beckmann) {
    D = beckmann_D(alpha2, std::min(dot(c.N, Ht), 1.f));
    G = beckmann_G1(p.alpha_x, cosNO) * beckmann_G1(p.alpha_x, cosNI);
  } else {
    D = ggx_D(alpha2, dot(c.N, Ht));
    G = ggx_G1(alpha2, cosNO) * ggx_G1(alpha2, cosNI);
  }
  const float G1o = beckmann ? beckmann_G1(p.alpha_x, cosNO) : ggx_G1(alpha2, cosNO);
  // Walter eq. 21 times |cos(omega_in)|, with the visible-normal pdf and the refraction
  // Jacobian eta^2 |omega_in.m| / |ht|^2 (Walter eq. 17).
  const float common = D * eta * eta / (cosNO * dot(ht, ht));
  pdf = G1o * std::abs(cosHO * cosHI) * common;
  const float out = G * std::abs(cosHI * cosHO) * common;
  return {out, out, out};
}

}  // namespace

Rgb microfacet_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in, float& pdf) {
  pdf = 0.f;
  const MicrofacetParams& p = c.microfacet;
  const bool refractive = c.type == ClosureType::kMicrofacetRefract;
  // Cycles passes sd->N, not the geometric normal, for the side test (bsdf.h bsdf_eval).
  const float cos_side = dot(ctx.N, omega_in);
  if ((cos_side < 0.f) != refractive || microfacet_singular(p)) return {};
  const float cosNO = dot(c.N, ctx.I), cosNI = dot(c.N, omega_in);
  // GGX picks the lobe by that side; Beckmann by the closure's own normal.
  const bool transmit =
      p.distribution == MicrofacetDistribution::kBeckmann ? cosNI < 0.f : cos_side < 0.f;
  return transmit ? eval_transmit(c, ctx.I, omega_in, cosNO, cosNI, pdf)
                  : eval_reflect(c, ctx.I, omega_in, cosNO, cosNI, pdf);
}

bool microfacet_sample(const Closure& c, const ClosureContext& ctx, Vec2f u, ClosureSample& s) {
  const MicrofacetParams& p = c.microfacet;
  const bool beckmann = p.distribution == MicrofacetDistribution::kBeckmann;
  const float cosNO = dot(c.N, ctx.I);
  if (!(cosNO > 0.f)) return false;
  const TangentFrame f(c.N, isotropic(p) ? Frame(c.N).s : p.T);
  float G1o;
  // Cycles' Beckmann sampling stretches by alpha_x on both axes (bsdf_microfacet_beckmann_sample).
  const Vec3f local_m = sample_stretched(f.to_local(ctx.I), p.alpha_x,
                                         beckmann ? p.alpha_x : p.alpha_y, u, beckmann, G1o);
  const Vec3f m = f.to_world(local_m);
  const float cos_m = local_m.z;
  const float alpha2 = p.alpha_x * p.alpha_y;
  s.singular = microfacet_singular(p);

  if (c.type == ClosureType::kMicrofacetReflect) {
    const float cosMO = dot(m, ctx.I);
    if (!(cosMO > 0.f)) return false;
    s.omega_in = 2.f * cosMO * m - ctx.I;
    if (!(dot(ctx.Ng, s.omega_in) > 0.f)) return false;
    if (s.singular) {
      s.pdf = 1.f;
      s.eval = fresnel_color(p, s.omega_in, m);
      return true;
    }
    const float cosNI = dot(c.N, s.omega_in);
    float D, G1i;
    if (isotropic(p)) {
      if (p.fresnel == FresnelMode::kClearcoat) {
        D = gtr1_D(cos_m, p.alpha_x);
        G1o = ggx_G1(0.0625f, cosNO);  // recomputed at the clearcoat's fixed alpha
        G1i = ggx_G1(0.0625f, cosNI);
      } else {
        D = beckmann ? beckmann_D(alpha2, cos_m) : ggx_D(alpha2, cos_m);
        G1i = beckmann ? beckmann_G1(p.alpha_x, cosNI) : ggx_G1(alpha2, cosNI);
      }
    } else {
      D = aniso_D(p, local_m);
      const Vec3f li = f.to_local(s.omega_in);
      G1i = beckmann ? beckmann_aniso_G1(p.alpha_x, p.alpha_y, cosNI, li.x, li.y)
                     : ggx_G1(projected_alpha2(p.alpha_x, p.alpha_y, li.x, li.y), cosNI);
    }
    const float common = G1o * D * 0.25f / cosNO;
    s.pdf = common;
    s.eval = fresnel_color(p, s.omega_in, m) * (G1i * common);
    return s.pdf > 0.f;
  }

  // Refraction: the closure only refracts; total internal reflection is no sample.
  const float eta = p.ior;
  bool inside;
  Vec3f T;
  const float fresnel = fresnel_dielectric(eta, m, ctx.I, T, inside);
  if (inside || fresnel == 1.f) return false;
  s.omega_in = T;
  if (s.singular || std::abs(eta - 1.f) < 1e-4f) {
    s.singular = true;
    s.pdf = 1.f;
    s.eval = {1.f, 1.f, 1.f};
    return true;
  }
  const float D = beckmann ? beckmann_D(alpha2, cos_m) : ggx_D(alpha2, cos_m);
  const float cosNI = dot(c.N, s.omega_in);
  const float G1i = beckmann ? beckmann_G1(p.alpha_x, cosNI) : ggx_G1(alpha2, cosNI);
  const float cosHI = dot(m, s.omega_in), cosHO = dot(m, ctx.I);
  const float Ht = eta * cosHI + cosHO;
  const float common = G1o * D * eta * eta / (cosNO * Ht * Ht);
  const float out = G1i * std::abs(cosHI * cosHO) * common;
  s.pdf = cosHO * std::abs(cosHI) * common;
  s.eval = {out, out, out};
  return s.pdf > 0.f;
}

bool sharp_reflection_sample(const Closure& c, const ClosureContext& ctx, ClosureSample& s) {
  const float cosNO = dot(c.N, ctx.I);
  if (!(cosNO > 0.f)) return false;
  s.omega_in = 2.f * cosNO * c.N - ctx.I;
  if (!(dot(ctx.Ng, s.omega_in) > 0.f)) return false;
  s.singular = true;
  s.pdf = 1.f;
  s.eval = {1.f, 1.f, 1.f};
  return true;
}

bool sharp_refraction_sample(const Closure& c, const ClosureContext& ctx, ClosureSample& s) {
  bool inside;
  const float fresnel = fresnel_dielectric(c.microfacet.ior, c.N, ctx.I, s.omega_in, inside);
  if (inside || fresnel == 1.f) return false;
  s.singular = true;
  s.pdf = 1.f;
  s.eval = {1.f, 1.f, 1.f};
  return true;
}

}  // namespace fb
