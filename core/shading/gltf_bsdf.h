// glTF's metallic-roughness BSDF (glTF 2.0 Appendix B, KHR_materials_transmission and
// KHR_materials_ior): a Lambertian diffuse base under a GGX specular layer, mixed by Fresnel, with
// metals reflecting through their base colour and a rough dielectric transmission lobe.
//
// - Microfacets: GGX / Trowbridge-Reitz with Smith's height-correlated masking-shadowing and the
//   rough dielectric BTDF of Walter et al. 2007, "Microfacet Models for Refraction through Rough
//   Surfaces" (eqs. 20, 21, 33, 34; Heitz 2014, "Understanding the Masking-Shadowing Function",
//   eq. 99 for G2). alpha = roughness^2, as glTF and Blender define roughness.
// - Fresnel: Schlick's approximation, F0 = ((ior - 1) / (ior + 1))^2 for dielectrics (0.04 at
//   ior 1.5), the base colour for metals; from the denser side, with the transmitted angle's cosine
//   and total internal reflection (Lagarde 2013, "Memo on Fresnel equations").
// - Mix (glTF Appendix B.3.5): f = (1 - m) [(1 - F)(1 - t) diffuse + (1 - F) t btdf + F spec] +
//   m Fm spec, with F at the microfacet normal for the microfacet lobes; the diffuse base is
//   weighted by the light crossing the layer twice instead (see eval()).
// - Sampling: microfacet normals from the distribution of visible normals (Heitz 2018, "Sampling
//   the GGX Distribution of Visible Normals"), cosine-weighted directions for the diffuse lobe,
//   one-sample MIS over the lobes (pdf() is the mixture's density, so the estimator stays
//   unbiased).
//
// Everything is in a local shading frame with the normal on +z and wo in the upper hemisphere:
// the caller flips the frame to the side the ray arrived from and passes the relative index of
// refraction `eta` = n(other side) / n(this side).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include <filmback/sampling.h>
#include <filmback/vec.h>

#include "core/shading/normals.h"

namespace fb {

struct BsdfParams {
  Rgb base_color{1.f, 1.f, 1.f};
  float metallic = 0.f;
  float roughness = 1.f;  // perceptual; GGX alpha = roughness^2
  float transmission = 0.f;
  float eta = 1.5f;      // relative index of refraction across the surface, seen from wo's side
  float specular = 1.f;  // KHR_materials_specular: scales the dielectric Fresnel; 0 is Lambertian
  // The interpolated normal before bump or normal mapping, in the local frame (+z: no mapping):
  // the diffuse lobe is shadowed where the two disagree, as Cycles does (bump_shadowing()).
  Vec3f smooth_normal{0.f, 0.f, 1.f};
};

class Bsdf {
 public:
  // The smallest alpha: below it the lobes are narrower than float directions can resolve.
  static constexpr float kMinAlpha = 1e-3f;

  explicit Bsdf(const BsdfParams& p)
      : base_(p.base_color),
        metallic_(std::clamp(p.metallic, 0.f, 1.f)),
        transmission_(std::clamp(p.transmission, 0.f, 1.f)),
        eta_(p.eta > 0.f ? p.eta : 1.f),
        specular_(std::clamp(p.specular, 0.f, 1.f)),
        smooth_(p.smooth_normal),
        bumped_(p.smooth_normal.z < 1.f - 1e-6f),
        alpha_(std::max(kMinAlpha, p.roughness * p.roughness)) {
    const float r = (eta_ - 1.f) / (eta_ + 1.f);
    f0_ = r * r;  // the same from either side
    // Cosine-weighted average of Schlick's F over the hemisphere: 2 int (1 - mu)^5 mu dmu = 1/21.
    // From the denser side total internal reflection adds to it: integrated numerically there.
    if (eta_ >= 1.f) {
      average_fresnel_ = specular_ * (f0_ + (1.f - f0_) / 21.f);
    } else {
      constexpr int kSteps = 64;
      float sum = 0.f;
      for (int i = 0; i < kSteps; ++i) {
        const float mu = (i + 0.5f) / kSteps;
        sum += fresnel(mu) * 2.f * mu / kSteps;
      }
      average_fresnel_ = std::min(sum, 0.999f);
    }
  }

  // f(wo, wi), without the cosine. Reflection when wi.z > 0, transmission when wi.z < 0.
  Rgb eval(Vec3f wo, Vec3f wi) const {
    if (!(wo.z > 0.f) || wi.z == 0.f) return {};
    if (wi.z > 0.f) {
      const Vec3f h = normalize(wo + wi);
      const float c = dot(wo, h);
      const float F = fresnel(c);
      const Rgb spec = Rgb{1.f, 1.f, 1.f} * (d(h) * g2(wo, wi) / (4.f * wo.z * wi.z));
      const float dielectric = 1.f - metallic_;
      // The diffuse base sees the light the specular layer let through on the way in and on
      // the way out, (1 - F(wo.n)) (1 - F(wi.n)), normalised by the hemispherical average so
      // that its albedo is exactly (1 - F(wo.n)) base: reciprocal and, unlike glTF's reference
      // (1 - F(wo.h)), never reflecting more than arrives at grazing angles (Kelemen and
      // Szirmay-Kalos 2001, with Schlick's F standing in for the specular albedo).
      float through = (1.f - fresnel(wo.z)) * (1.f - fresnel(wi.z)) / (1.f - average_fresnel_);
      if (bumped_) through *= bump_shadowing(smooth_, wi);
      return base_ * (dielectric * through * (1.f - transmission_) * kInvPi) +
             spec * (dielectric * F) + spec * metal_fresnel(c) * metallic_;
    }
    Vec3f h;
    float jacobian;
    if (!refraction_half_vector(wo, wi, h, jacobian)) return {};
    const float F = fresnel(dot(wo, h));
    // Walter eq. 21, divided by eta^2 because radiance is carried (pbrt 4e §9.5.2): the solid
    // angle compresses on entering a denser medium, so the BTDF is not symmetric.
    const float value = d(h) * g2(wo, wi) * std::abs(dot(wi, h)) * dot(wo, h) * jacobian /
                        (eta_ * eta_ * wo.z * std::abs(wi.z));
    return base_ * ((1.f - metallic_) * transmission_ * (1.f - F) * value);
  }

  // The solid-angle density with which sample() returns wi.
  float pdf(Vec3f wo, Vec3f wi) const {
    if (!(wo.z > 0.f) || wi.z == 0.f) return 0.f;
    const float p_diffuse = diffuse_probability(wo);
    if (wi.z > 0.f) {
      const Vec3f h = normalize(wo + wi);
      const float c = dot(wo, h);
      const float specular = visible_normal_pdf(wo, h) / (4.f * c) * reflect_probability(c);
      return p_diffuse * wi.z * kInvPi + (1.f - p_diffuse) * specular;
    }
    Vec3f h;
    float jacobian;
    if (!refraction_half_vector(wo, wi, h, jacobian)) return 0.f;
    const float c = dot(wo, h);
    return (1.f - p_diffuse) * visible_normal_pdf(wo, h) * std::abs(dot(wi, h)) * jacobian *
           (1.f - reflect_probability(c));
  }

  struct Sample {
    Vec3f wi;
    Rgb weight;  // f |cos wi| / pdf
    float pdf = 0.f;
  };

  // Draws wi from u_lobe (which lobe) and u (the direction). False when the sample carries no
  // light: below the surface for a reflection, total internal reflection's other branch, etc.
  bool sample(Vec3f wo, float u_lobe, Vec2f u, Sample& s) const {
    if (!(wo.z > 0.f)) return false;
    const float p_diffuse = diffuse_probability(wo);
    if (u_lobe < p_diffuse) {
      s.wi = sample_cosine_hemisphere(u);
    } else {
      const Vec3f h = sample_visible_normal(wo, u);
      const float c = dot(wo, h);
      if (!(c > 0.f)) return false;
      // Reuse the lobe number for the reflect/refract choice: it is uniform within its interval.
      const float v = (u_lobe - p_diffuse) / (1.f - p_diffuse);
      // A reflection that leaves below the surface, or a refraction that stays above it, is a
      // path of no light: eval() and pdf() would read it as the other lobe.
      if (v < reflect_probability(c)) {
        s.wi = h * (2.f * c) - wo;
        if (!(s.wi.z > 0.f)) return false;
      } else if (!refract(wo, h, s.wi) || !(s.wi.z < 0.f)) {
        return false;
      }
    }
    if (s.wi.z == 0.f) return false;
    s.pdf = pdf(wo, s.wi);
    if (!(s.pdf > 0.f)) return false;
    s.weight = eval(wo, s.wi) * (std::abs(s.wi.z) / s.pdf);
    return is_finite(s.weight);
  }

  float alpha() const { return alpha_; }

  // Each lobe's weight as Cycles writes a closure's (its colour and share, Fresnel left in its
  // evaluation), for the DiffCol, GlossCol and TransCol passes (docs/blender.md, "Passes"): the
  // diffuse base; one specular layer over the whole surface (the dielectric's reflects unless
  // KHR_materials_specular is 0, the metal's always); the transmission under it.
  Rgb diffuse_weight() const { return base_ * ((1.f - metallic_) * (1.f - transmission_)); }
  Rgb glossy_weight() const {
    const float weight = metallic_ + (specular_ > 0.f ? 1.f - metallic_ : 0.f);
    return {weight, weight, weight};
  }
  Rgb transmission_weight() const { return base_ * ((1.f - metallic_) * transmission_); }

 private:
  static constexpr float kInvPi = std::numbers::inv_pi_v<float>;

  // GGX normal distribution D(h) (Walter eq. 33), h in the upper hemisphere.
  float d(Vec3f h) const {
    const float a2 = alpha_ * alpha_;
    const float k = h.z * h.z * (a2 - 1.f) + 1.f;
    return a2 / (std::numbers::pi_v<float> * k * k);
  }
  // Smith's Lambda for GGX (Heitz 2014 eq. 86).
  float lambda(Vec3f w) const {
    const float cos2 = w.z * w.z;
    const float tan2 = std::max(0.f, 1.f - cos2) / cos2;
    return 0.5f * (std::sqrt(1.f + alpha_ * alpha_ * tan2) - 1.f);
  }
  float g1(Vec3f w) const { return 1.f / (1.f + lambda(w)); }
  float g2(Vec3f wo, Vec3f wi) const { return 1.f / (1.f + lambda(wo) + lambda(wi)); }

  // D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z (Heitz 2018 eq. 1).
  float visible_normal_pdf(Vec3f wo, Vec3f h) const {
    const float c = dot(wo, h);
    return c > 0.f && h.z > 0.f ? g1(wo) * c * d(h) / wo.z : 0.f;
  }

  // Heitz 2018, listing 1, for an isotropic alpha.
  Vec3f sample_visible_normal(Vec3f wo, Vec2f u) const {
    const Vec3f vh = normalize(Vec3f{alpha_ * wo.x, alpha_ * wo.y, wo.z});
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const Vec3f t1 =
        len2 > 0.f ? Vec3f{-vh.y, vh.x, 0.f} * (1.f / std::sqrt(len2)) : Vec3f{1.f, 0.f, 0.f};
    const Vec3f t2 = cross(vh, t1);
    const float r = std::sqrt(u.x);
    const float phi = 2.f * std::numbers::pi_v<float> * u.y;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.f + vh.z);
    const float p2 = (1.f - s) * std::sqrt(std::max(0.f, 1.f - p1 * p1)) + s * r * std::sin(phi);
    const Vec3f nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.f, 1.f - p1 * p1 - p2 * p2));
    return normalize(Vec3f{alpha_ * nh.x, alpha_ * nh.y, std::max(1e-6f, nh.z)});
  }

  // Schlick's dielectric Fresnel for the cosine c = wo.h on wo's side; from the denser side the
  // transmitted angle's cosine replaces it, and beyond the critical angle all is reflected.
  float fresnel(float c) const {
    if (eta_ < 1.f) {
      const float sin2_t = (1.f - c * c) / (eta_ * eta_);
      if (sin2_t >= 1.f) return 1.f;
      c = std::sqrt(1.f - sin2_t);
    }
    const float m = 1.f - c, m2 = m * m;
    return specular_ * (f0_ + (1.f - f0_) * m2 * m2 * m);
  }
  Rgb metal_fresnel(float c) const {
    const float m = 1.f - c, m2 = m * m;
    return base_ + (Rgb{1.f, 1.f, 1.f} - base_) * (m2 * m2 * m);
  }

  // Probability of reflecting rather than refracting at microfacet h: the reflected share of the
  // energy the two microfacet lobes carry there (1 without transmission).
  float reflect_probability(float c) const {
    const float F = fresnel(c);
    const float reflect = (1.f - metallic_) * F + metallic_ * luminance(metal_fresnel(c));
    const float refract = (1.f - metallic_) * transmission_ * (1.f - F) * luminance(base_);
    return reflect + refract > 0.f ? reflect / (reflect + refract) : 1.f;
  }
  // Probability of the diffuse lobe: its share of the energy estimated at the normal, wo.z.
  float diffuse_probability(Vec3f wo) const {
    const float F = fresnel(wo.z);
    const float diffuse = (1.f - metallic_) * (1.f - transmission_) * (1.f - F) * luminance(base_);
    const float microfacet =
        (1.f - metallic_) * (F + transmission_ * (1.f - F) * luminance(base_)) +
        metallic_ * luminance(metal_fresnel(wo.z));
    return diffuse + microfacet > 0.f ? diffuse / (diffuse + microfacet) : 0.f;
  }

  // wi = refraction of wo at microfacet h (Snell), false under total internal reflection.
  bool refract(Vec3f wo, Vec3f h, Vec3f& wi) const {
    const float c = dot(wo, h);
    const float sin2_t = (1.f - c * c) / (eta_ * eta_);
    if (sin2_t >= 1.f) return false;
    const float cos_t = std::sqrt(1.f - sin2_t);
    wi = -wo / eta_ + h * (c / eta_ - cos_t);
    return true;
  }
  // The microfacet normal that refracts wo into wi (Walter eq. 16, facing +z) and the Jacobian
  // |dh/dwi| / |wi.h| = eta^2 / (wo.h + eta wi.h)^2 (Walter eq. 17, its |wi.h| factored out).
  bool refraction_half_vector(Vec3f wo, Vec3f wi, Vec3f& h, float& jacobian) const {
    if (transmission_ <= 0.f || metallic_ >= 1.f) return false;
    h = wo + wi * eta_;
    const float len = length(h);
    if (!(len > 0.f)) return false;
    h = h / len;
    if (h.z < 0.f) h = -h;
    // Both directions must see the microfacet from their own side.
    if (!(dot(wo, h) > 0.f && dot(wi, h) < 0.f) || !(h.z > 0.f)) return false;
    const float denom = dot(wo, h) + eta_ * dot(wi, h);
    jacobian = eta_ * eta_ / (denom * denom);
    return true;
  }

  Rgb base_;
  float metallic_, transmission_, eta_, specular_;
  Vec3f smooth_;
  bool bumped_;
  float alpha_, f0_ = 0.04f, average_fresnel_ = 0.f;
};

}  // namespace fb
