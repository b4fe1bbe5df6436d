#include "core/shading/bsdf_microfacet_multi.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/math/constants.h"
#include "core/math/safe_math.h"
#include "core/shading/fresnel.h"
#include "core/shading/hemisphere.h"

namespace fb {
namespace {

constexpr int kMaxOrder = 10;  // bounces of the walk

// Cycles' LCG (kernel/sample/lcg.h lcg_step_float): x' = 1103515245 x + 12345 mod 2^32.
struct Lcg {
  uint32_t state;
  float next() {
    state = 1103515245u * state + 12345u;
    return float(state) * (1.f / float(0xFFFFFFFFu));
  }
};

// A 32-bit seed from six floats (the murmur3 finaliser over their bits, chained).
uint32_t hash_seed(Vec3f a, Vec3f b) {
  uint32_t h = 0x9E3779B9u;
  for (float v : {a.x, a.y, a.z, b.x, b.y, b.z}) {
    h ^= std::bit_cast<uint32_t>(v);
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    h ^= h >> 16;
  }
  // lcg_init: one step before use.
  return 1103515245u * h + 12345u;
}

struct Alpha {
  float x, y;
};

float D_ggx(Vec3f wm, float alpha) {
  const float z2 = wm.z * wm.z, a2 = alpha * alpha;
  const float tmp = (1.f - z2) + a2 * z2;
  return a2 / std::max(kPiF * tmp * tmp, 1e-7f);
}
float D_ggx_aniso(Vec3f wm, Alpha a) {
  const float sx = -wm.x / a.x, sy = -wm.y / a.y;
  const float tmp = wm.z * wm.z + sx * sx + sy * sy;
  return 1.f / std::max(kPiF * tmp * tmp * a.x * a.y, 1e-7f);
}
float D_of(Vec3f wm, Alpha a) {
  return a.x == a.y ? D_ggx(wm, a.x) : D_ggx_aniso(wm, a);
}

// Slopes of unit-roughness GGX visible normals (the supplemental code of Heitz et al. 2016).
Vec2f sample_p22_11(float cos_i, float rx, float ry) {
  if (cos_i > 0.9999f || std::abs(cos_i) < 1e-6f) {
    const float r = std::sqrt(rx / std::max(1.f - rx, 1e-7f)), phi = 2.f * kPiF * ry;
    return {r * std::cos(phi), r * std::sin(phi)};
  }
  const float sin_i = safe_sqrt(1.f - cos_i * cos_i), tan_i = sin_i / cos_i;
  const float proj_a = 0.5f * (cos_i + 1.f);
  if (proj_a < 0.0001f) return {0.f, 0.f};
  const float A = 2.f * rx * proj_a / cos_i - 1.f;
  float tmp = A * A - 1.f;
  if (std::abs(tmp) < 1e-7f) return {0.f, 0.f};
  tmp = 1.f / tmp;
  const float D = safe_sqrt(tan_i * tan_i * tmp * tmp - (A * A - tan_i * tan_i) * tmp);
  const float slope_x2 = tan_i * tmp + D;
  const float slope_x = (A < 0.f || slope_x2 > 1.f / tan_i) ? tan_i * tmp - D : slope_x2;
  const float U2 = ry >= 0.5f ? 2.f * (ry - 0.5f) : 2.f * (0.5f - ry);
  const float z = (U2 * (U2 * (U2 * 0.27385f - 0.73369f) + 0.46341f)) /
                  (U2 * (U2 * (U2 * 0.093073f + 0.309420f) - 1.f) + 0.597999f);
  const float slope_y = z * std::sqrt(1.f + slope_x * slope_x);
  return {slope_x, ry >= 0.5f ? slope_y : -slope_y};
}

Vec3f sample_vndf(Vec3f wi, Alpha a, float rx, float ry) {
  const Vec3f wi_11 = normalize(Vec3f{a.x * wi.x, a.y * wi.y, wi.z});
  const Vec2f s = sample_p22_11(wi_11.z, rx, ry);
  const float len = std::sqrt(wi_11.x * wi_11.x + wi_11.y * wi_11.y);
  const float cp = len > 0.f ? wi_11.x / len : 0.f, sp = len > 0.f ? wi_11.y / len : 0.f;
  const float sx = a.x * (cp * s.x - sp * s.y), sy = a.y * (sp * s.x + cp * s.y);
  return normalize(Vec3f{-sx, -sy, 1.f});
}

Vec3f sample_phase_glossy(Vec3f wi, Vec3f wm) {
  return -wi + 2.f * dot(wi, wm) * wm;
}

float eval_phase_glossy(Vec3f w, float lambda, Vec3f wo, Alpha a) {
  if (w.z > 0.9999f) return 0.f;
  const Vec3f wh = normalize(wo - w);
  if (wh.z < 0.f) return 0.f;
  const float p_area = w.z < -0.9999f ? 1.f : lambda * w.z;
  const float dot_w_wh = dot(-w, wh);
  if (dot_w_wh < 0.f) return 0.f;
  return std::max(0.f, dot_w_wh) * 0.25f / std::max(p_area * dot_w_wh, 1e-7f) * D_of(wh, a);
}

Vec3f sample_phase_glass(Vec3f wi, float eta, Vec3f wm, float r, bool& outside) {
  const float cos_i = dot(wi, wm);
  if (r < fresnel_dielectric_cos(cos_i, eta)) {
    outside = true;
    return -wi + 2.f * wm * cos_i;
  }
  outside = false;
  const float inv_eta = 1.f / eta;
  const float cos_t = -safe_sqrt(1.f - (1.f - cos_i * cos_i) * inv_eta * inv_eta);
  return normalize(wm * (cos_i * inv_eta + cos_t) - wi * inv_eta);
}

float eval_phase_glass(Vec3f w, float lambda, Vec3f wo, bool wo_outside, Alpha a, float eta) {
  if (w.z > 0.9999f) return 0.f;
  const float p_area = w.z < -0.9999f ? 1.f : lambda * w.z;
  if (wo_outside) {
    const Vec3f wh = normalize(wo - w);
    if (wh.z < 0.f) return 0.f;
    const float dot_w_wh = dot(-w, wh);
    return fresnel_dielectric_cos(dot_w_wh, eta) * std::max(0.f, dot_w_wh) * D_ggx(wh, a.x) *
           0.25f / (p_area * dot_w_wh);
  }
  Vec3f wh = normalize(wo * eta - w);
  if (wh.z < 0.f) wh = -wh;
  const float dot_w_wh = dot(-w, wh), dot_wo_wh = dot(wo, wh);
  if (dot_w_wh < 0.f) return 0.f;
  const float temp = dot_w_wh + eta * dot_wo_wh;
  return (1.f - fresnel_dielectric_cos(dot_w_wh, eta)) * std::max(0.f, dot_w_wh) *
         std::max(0.f, -dot_wo_wh) * D_ggx(wh, a.x) / (p_area * temp * temp);
}

// Smith's Lambda for GGX, signed for downward directions (Heitz et al. 2016 supplemental).
float mf_lambda(Vec3f w, Alpha a) {
  if (w.z > 0.9999f) return 0.f;
  if (w.z < -0.9999f) return -0.9999f;
  const float inv_wz2 = 1.f / std::max(w.z * w.z, 1e-7f);
  const float wax = w.x * a.x, way = w.y * a.y;
  float v = std::sqrt(1.f + (wax * wax + way * way) * inv_wz2);
  if (w.z <= 0.f) v = -v;
  return 0.5f * (v - 1.f);
}
// The uniform height distribution's inverse CDF and CDF.
float mf_invC1(float h) {
  return 2.f * std::clamp(h, 0.f, 1.f) - 1.f;
}
float mf_C1(float h) {
  return std::clamp(0.5f * (h + 1.f), 0.f, 1.f);
}
float mf_G1(Vec3f w, float C1, float lambda) {
  if (w.z > 0.9999f) return 1.f;
  if (w.z < 1e-5f) return 0.f;
  return std::pow(C1, lambda);
}
// The next height along w, or false when the walk leaves the surface.
bool mf_sample_height(Vec3f w, float& h, float& C1, float& G1, float lambda, float U) {
  if (w.z > 0.9999f) return false;
  if (w.z < -0.9999f) {
    C1 *= U;
    h = mf_invC1(C1);
    G1 = mf_G1(w, C1, lambda);
  } else if (std::abs(w.z) >= 0.0001f) {
    if (U > 1.f - G1) return false;
    if (lambda >= 0.f)
      C1 = 1.f;
    else
      C1 *= std::pow(1.f - U, -1.f / lambda);
    h = mf_invC1(C1);
    G1 = mf_G1(w, C1, lambda);
  }
  return true;
}

// Fits of the single-scattering albedo (mf_ggx_albedo, mf_ggx_transmission_albedo) that weight
// the pdf's cosine lobe.
float mf_ggx_albedo(float r) {
  float albedo = 0.806495f * std::exp(-1.98712f * r * r) + 0.199531f;
  albedo -=
      ((((((1.76741f * r - 8.43891f) * r + 15.784f) * r - 14.398f) * r + 6.45221f) * r - 1.19722f) *
           r +
       0.027803f) *
          r +
      0.00568739f;
  return std::clamp(albedo, 0.f, 1.f);
}
float mf_ggx_transmission_albedo(float a, float ior) {
  if (ior < 1.f) ior = 1.f / ior;
  a = std::clamp(a, 0.f, 1.f);
  ior = std::clamp(ior, 1.f, 3.f);
  const float I_1 = 0.0476898f * std::exp(-0.978352f * (ior - 0.65657f) * (ior - 0.65657f)) -
                    0.033756f * ior + 0.993261f;
  const float R_1 =
      (((0.116991f * a - 0.270369f) * a + 0.0501366f) * a - 0.00411511f) * a + 1.00008f;
  const float I_2 = (((-2.08704f * ior + 26.3298f) * ior - 127.906f) * ior + 292.958f) * ior -
                    287.946f + 199.803f / (ior * ior) - 101.668f / (ior * ior * ior);
  const float R_2 =
      ((((5.3725f * a - 24.9307f) * a + 22.7437f) * a - 3.40751f) * a + 0.0986325f) * a +
      0.00493504f;
  return std::clamp(1.f + I_2 * R_2 * 0.0019127f - (1.f - I_1) * (1.f - R_1) * 9.3205f, 0.f, 1.f);
}

float mf_ggx_pdf(Vec3f wi, Vec3f wo, Alpha a) {
  const float D = D_of(normalize(wi + wo), a);
  const float lambda = mf_lambda(wi, a);
  const float single = 0.25f * D / std::max((1.f + lambda) * wi.z, 1e-7f);
  const float albedo = mf_ggx_albedo(a.x == a.y ? a.x : std::sqrt(a.x * a.y));
  return albedo * single + (1.f - albedo) * wo.z * kInvPi;
}

float mf_glass_pdf(Vec3f wi, Vec3f wo, float alpha, float eta) {
  const bool reflective = wi.z * wo.z > 0.f;
  const Vec3f h = wi + (reflective ? wo : wo * eta);
  const float wh_len = length(h);
  Vec3f wh = h / wh_len;
  if (wh.z < 0.f) wh = -wh;
  const Vec3f r_wi = wi.z < 0.f ? -wi : wi;
  const Alpha a{alpha, alpha};
  const float lambda = mf_lambda(r_wi, a);
  const float D = D_ggx(wh, alpha);
  const float fresnel = fresnel_dielectric_cos(dot(r_wi, wh), eta);
  const float multiscatter = std::abs(wo.z * kInvPi);
  if (reflective) {
    const float single = 0.25f * D / std::max((1.f + lambda) * r_wi.z, 1e-7f);
    const float albedo = mf_ggx_albedo(alpha);
    return fresnel * (albedo * single + (1.f - albedo) * multiscatter);
  }
  const float single = std::abs(dot(r_wi, wh) * dot(wo, wh) * D * eta * eta /
                                std::max((1.f + lambda) * r_wi.z * wh_len * wh_len, 1e-7f));
  const float albedo = mf_ggx_transmission_albedo(alpha, eta);
  return (1.f - fresnel) * (albedo * single + (1.f - albedo) * multiscatter);
}

struct Walk {
  Rgb color, cspec0;
  Alpha alpha;
  float eta;
  bool use_fresnel;
};

// mf_eval (bsdf_microfacet_multi_impl.h) for the glossy or the glass phase function.
template <bool kGlass>
Rgb mf_eval(Vec3f wi, Vec3f wo, bool wo_outside, const Walk& w, Lcg& lcg) {
  bool swapped = false;
  if (kGlass && wi.z * wo.z < 0.f) {
    if (-wo.z < wi.z) {
      swapped = true;
      const Vec3f tmp = -wo;
      wo = -wi;
      wi = tmp;
    }
  } else if (wo.z < wi.z) {
    swapped = true;
    std::swap(wi, wo);
  }
  if (wi.z < 1e-5f || (wo.z < 1e-5f && wo_outside) || (wo.z > -1e-5f && !wo_outside)) return {};

  const Alpha a = w.alpha;
  float lambda_r = mf_lambda(-wi, a);
  const float shadowing_lambda = mf_lambda(wo_outside ? wo : -wo, a);
  const Vec3f wh = normalize(wi + wo);
  Rgb eval, throughput{1.f, 1.f, 1.f};
  if constexpr (kGlass) {
    float v = eval_phase_glass(-wi, lambda_r, wo, wo_outside, a, w.eta);
    if (wo_outside)
      v *= -lambda_r / (shadowing_lambda - lambda_r);
    else  // -lambda_r B(-lambda_r, shadowing_lambda + 1), B Euler's beta function
      v *= -lambda_r * std::exp(std::lgamma(-lambda_r) + std::lgamma(shadowing_lambda + 1.f) -
                                std::lgamma(-lambda_r + shadowing_lambda + 1.f));
    eval = {v, v, v};
  } else {
    const float G2 = 1.f / (1.f - (lambda_r + 1.f) + shadowing_lambda);
    const float v = G2 * 0.25f / wi.z * D_of(wh, a);
    eval = {v, v, v};
  }
  const float F0 = fresnel_dielectric_cos(1.f, w.eta);
  if (w.use_fresnel) {
    throughput = interpolate_fresnel_color(wi, wh, w.eta, F0, w.cspec0);
    eval *= throughput;
  }

  Vec3f wr = -wi;
  float hr = 1.f, C1_r = 1.f, G1_r = 0.f;
  bool outside = true;
  for (int order = 0; order < kMaxOrder; ++order) {
    if (!mf_sample_height(wr, hr, C1_r, G1_r, lambda_r, lcg.next())) break;
    const float ry = lcg.next(), rx = lcg.next();
    const Vec3f wm = sample_vndf(-wr, a, rx, ry);
    const auto next_event = [&] {
      return mf_G1(wo_outside ? wo : -wo, mf_C1(outside == wo_outside ? hr : -hr),
                   shadowing_lambda);
    };
    const auto glass_phase = [&] {
      return outside ? eval_phase_glass(wr, lambda_r, wo, wo_outside, a, w.eta)
                     : eval_phase_glass(wr, lambda_r, -wo, !wo_outside, a, 1.f / w.eta);
    };
    if constexpr (kGlass) {
      if (order == 0 && w.use_fresnel) eval = throughput * (glass_phase() * next_event());
    }
    if (order > 0) {
      if constexpr (kGlass)
        eval += throughput * (glass_phase() * next_event());
      else
        eval += throughput * throughput * (eval_phase_glossy(wr, lambda_r, wo, a) * next_event());
    }
    if (order + 1 < kMaxOrder) {
      if constexpr (kGlass) {
        bool next_outside;
        const Vec3f wi_prev = -wr;
        wr = sample_phase_glass(-wr, outside ? w.eta : 1.f / w.eta, wm, lcg.next(), next_outside);
        if (!next_outside) {
          outside = !outside;
          wr = -wr;
          hr = -hr;
        }
        if (w.use_fresnel && !next_outside)
          throughput *= w.color;
        else if (w.use_fresnel && order > 0)
          throughput *= interpolate_fresnel_color(wi_prev, wm, w.eta, F0, w.cspec0);
      } else {
        if (w.use_fresnel && order > 0)
          throughput *= interpolate_fresnel_color(-wr, wm, w.eta, F0, w.cspec0);
        wr = sample_phase_glossy(-wr, wm);
      }
      lambda_r = mf_lambda(wr, a);
      if (!w.use_fresnel) throughput *= w.color;
      C1_r = mf_C1(hr);
      G1_r = mf_G1(wr, C1_r, lambda_r);
    }
  }
  if (swapped) eval *= std::abs(wi.z / wo.z);
  return eval;
}

// mf_sample: the walk from wi; its exit direction in wo and its throughput.
template <bool kGlass>
Rgb mf_sample(Vec3f wi, Vec3f& wo, const Walk& w, Lcg& lcg) {
  const Alpha a = w.alpha;
  Rgb throughput{1.f, 1.f, 1.f};
  Vec3f wr = -wi;
  float lambda_r = mf_lambda(wr, a), hr = 1.f, C1_r = 1.f, G1_r = 0.f;
  bool outside = true;
  const float F0 = fresnel_dielectric_cos(1.f, w.eta);
  for (int order = 0; order < kMaxOrder; ++order) {
    if (!mf_sample_height(wr, hr, C1_r, G1_r, lambda_r, lcg.next())) {
      wo = outside ? wr : -wr;
      return throughput;
    }
    const float ry = lcg.next(), rx = lcg.next();
    const Vec3f wm = sample_vndf(-wr, a, rx, ry);
    // The first bounce's colour is in the closure's weight.
    if (!w.use_fresnel && order > 0) throughput *= w.color;
    if constexpr (kGlass) {
      bool next_outside;
      const Vec3f wi_prev = -wr;
      wr = sample_phase_glass(-wr, outside ? w.eta : 1.f / w.eta, wm, lcg.next(), next_outside);
      if (!next_outside) {
        hr = -hr;
        wr = -wr;
        outside = !outside;
      }
      if (w.use_fresnel) {
        if (!next_outside) {
          throughput *= w.color;
        } else {
          const Rgb t = interpolate_fresnel_color(wi_prev, wm, w.eta, F0, w.cspec0);
          throughput = order == 0 ? t : throughput * t;
        }
      }
    } else {
      if (w.use_fresnel) {
        const Rgb t = interpolate_fresnel_color(-wr, wm, w.eta, F0, w.cspec0);
        throughput = order == 0 ? t : throughput * t;
      }
      wr = sample_phase_glossy(-wr, wm);
    }
    lambda_r = mf_lambda(wr, a);
    G1_r = mf_G1(wr, C1_r, lambda_r);
  }
  wo = {0.f, 0.f, 1.f};
  return {};
}

Walk walk_of(const MicrofacetParams& p) {
  return {p.color, p.cspec0, {p.alpha_x, p.alpha_y}, p.ior, p.fresnel != FresnelMode::kNone};
}

bool singular(const MicrofacetParams& p) {
  return p.alpha_x * p.alpha_y < 1e-7f;
}

}  // namespace

Rgb multi_ggx_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in, float& pdf) {
  pdf = 0.f;
  const MicrofacetParams& p = c.microfacet;
  if (singular(p)) return {};
  Lcg lcg{hash_seed(ctx.I, omega_in)};
  Walk w = walk_of(p);
  if (c.type == ClosureType::kMultiGgxReflect) {
    // Cycles passes sd->N as the side test here too (bsdf.h bsdf_eval).
    if (dot(ctx.N, omega_in) < 0.f) return {};
    if (dot(c.N, ctx.I) <= 0.f || dot(c.N, omega_in) <= 0.f) return {};
    const TangentFrame f(c.N, p.alpha_x != p.alpha_y ? p.T : Frame(c.N).s);
    const Vec3f li = f.to_local(ctx.I), lo = f.to_local(omega_in);
    pdf = mf_ggx_pdf(li, lo, w.alpha);
    if (!(pdf > 0.f)) return pdf = 0.f, Rgb{};
    return mf_eval<false>(li, lo, true, w, lcg);
  }
  const Frame f(c.N);
  const Vec3f li = f.to_local(ctx.I), lo = f.to_local(omega_in);
  const bool transmission = lo.z < 0.f;
  w.use_fresnel = !transmission && w.use_fresnel;
  if (transmission) w.cspec0 = w.color;
  pdf = mf_glass_pdf(li, lo, p.alpha_x, p.ior);
  return mf_eval<true>(li, lo, !transmission, w, lcg);
}

bool multi_ggx_sample(const Closure& c, const ClosureContext& ctx, Vec2f u, ClosureSample& s) {
  const MicrofacetParams& p = c.microfacet;
  const Vec3f N = c.N;
  if (c.type == ClosureType::kMultiGgxReflect) {
    if (dot(N, ctx.I) <= 0.f) return false;
    if (singular(p)) {
      s.omega_in = 2.f * dot(N, ctx.I) * N - ctx.I;
      if (dot(ctx.Ng, s.omega_in) <= 0.f) return false;
      s.singular = true;
      s.pdf = 1.f;
      s.eval = {1.f, 1.f, 1.f};
      return true;
    }
  } else if (singular(p)) {
    bool inside;
    Vec3f T;
    const float F = fresnel_dielectric(p.ior, N, ctx.I, T, inside);
    const Vec3f R = (2.f * std::abs(dot(N, ctx.I))) * (inside ? -N : N) - ctx.I;
    s.omega_in = u.x < F ? R : T;
    s.singular = true;
    s.pdf = 1.f;
    s.eval = {1.f, 1.f, 1.f};
    return true;
  }
  Lcg lcg{hash_seed(ctx.I, Vec3f{u.x, u.y, 0.f})};
  const Walk w = walk_of(p);
  if (c.type == ClosureType::kMultiGgxReflect) {
    const TangentFrame f(N, p.alpha_x != p.alpha_y ? p.T : Frame(N).s);
    const Vec3f li = f.to_local(ctx.I);
    Vec3f lo;
    const Rgb throughput = mf_sample<false>(li, lo, w, lcg);
    s.omega_in = f.to_world(lo);
    if (dot(ctx.Ng, s.omega_in) <= 0.f) return false;
    s.pdf = std::max(0.f, mf_ggx_pdf(li, lo, w.alpha));
    s.eval = throughput * s.pdf;
    return s.pdf > 0.f;
  }
  const Frame f(N);
  const Vec3f li = f.to_local(ctx.I);
  Vec3f lo;
  const Rgb throughput = mf_sample<true>(li, lo, w, lcg);
  s.pdf = mf_glass_pdf(li, lo, p.alpha_x, p.ior);
  s.eval = throughput * s.pdf;
  s.omega_in = f.to_world(lo);
  return s.pdf > 0.f;
}

}  // namespace fb
