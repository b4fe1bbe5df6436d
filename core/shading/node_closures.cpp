// Blender 3.4's closure nodes turned into closures, line by line as Cycles 3.4's
// svm_node_closure_bsdf (kernel/svm/closure.h) does it, with the closures' setup functions
// (bsdf_*_setup in kernel/closure/). `weight` is the node's mix weight (sd->svm_closure_weight
// times mix_weight); the Principled BSDF's svm_closure_weight is white, the other nodes' is
// their Color.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/math/safe_math.h"
#include "core/shading/bsdf_oren_nayar.h"
#include "core/shading/bsdf_principled_sheen.h"
#include "core/shading/fresnel.h"
#include "core/shading/surface.h"

namespace fb {
namespace {

float saturate(float v) {
  return std::clamp(v, 0.f, 1.f);
}
Rgb saturate(Rgb c) {
  return {saturate(c.x), saturate(c.y), saturate(c.z)};
}
// Rodrigues' rotation of v about the unit axis by `angle` radians (util/math.h
// rotate_around_axis).
Vec3f rotate_around_axis(Vec3f v, Vec3f axis, float angle) {
  const float s = std::sin(angle), c = std::cos(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.f - c));
}

// bsdf_microfacet_fresnel_color: the Fresnel colour at the normal scales the sample weight (the
// clearcoat's by its 0.25 clearcoat factor too).
void scale_by_fresnel(Closure& c, Vec3f I) {
  const MicrofacetParams& p = c.microfacet;
  Rgb F = interpolate_fresnel_color(I, c.N, p.ior, fresnel_dielectric_cos(1.f, p.ior), p.cspec0);
  if (p.fresnel == FresnelMode::kClearcoat) F *= 0.25f * p.clearcoat;
  c.sample_weight *= average(F);
}

MicrofacetParams microfacet(float alpha_x, float alpha_y, float ior, Vec3f T, Rgb cspec0, Rgb color,
                            FresnelMode fresnel,
                            MicrofacetDistribution d = MicrofacetDistribution::kGgx) {
  return {alpha_x, alpha_y, ior, T, cspec0, color, 0.f, d, fresnel};
}

// bsdf_microfacet_ggx_setup / _beckmann_setup (alphas saturated), and the refraction setups,
// which are isotropic.
void single_scatter_setup(Closure& c) {
  MicrofacetParams& p = c.microfacet;
  p.alpha_x = saturate(p.alpha_x);
  p.alpha_y = c.type == ClosureType::kMicrofacetRefract ? p.alpha_x : saturate(p.alpha_y);
  p.cspec0 = saturate(p.cspec0);
}

// bsdf_microfacet_multi_ggx_common_setup; the glossy lobe's tangent defaults to +x.
void multi_scatter_setup(Closure& c) {
  MicrofacetParams& p = c.microfacet;
  if (c.type == ClosureType::kMultiGgxReflect) {
    if (p.T.x == 0.f && p.T.y == 0.f && p.T.z == 0.f) p.T = {1.f, 0.f, 0.f};
    p.alpha_x = std::clamp(p.alpha_x, 1e-4f, 1.f);
    p.alpha_y = std::clamp(p.alpha_y, 1e-4f, 1.f);
  } else {
    p.alpha_x = std::clamp(p.alpha_x, 1e-4f, 1.f);
    p.alpha_y = p.alpha_x;
    p.ior = std::max(0.f, p.ior);
  }
  p.color = saturate(p.color);
  p.cspec0 = saturate(p.cspec0);
}

// The tangent: Cycles' default is a radial tangent about the object's Z axis (a Tangent node the
// graph adds to the unlinked socket); without one, any tangent of N (it only matters for
// Anisotropic != 0, docs/blender.md "Blender materials"). Anisotropic Rotation turns it about N.
Vec3f principled_tangent(const PrincipledInputs& in, Vec3f N) {
  Vec3f T = dot(in.tangent, in.tangent) > 0.f ? in.tangent : Frame(N).s;
  if (in.anisotropic_rotation != 0.f)
    T = rotate_around_axis(T, N, in.anisotropic_rotation * 2.f * std::numbers::pi_v<float>);
  return T;
}

}  // namespace

// What svm_node_closure_bsdf's CLOSURE_BSDF_PRINCIPLED_ID case computes once for all the lobes.
struct Surface::PrincipledCommon {
  const PrincipledInputs& in;
  Rgb weight;  // the node's
  Vec3f N, I, T;
  float ior;      // relative: its inverse seen from the back
  float fresnel;  // the dielectric Fresnel factor at N for ior
  // The lobes' shares: metallic takes from diffuse and transmission, transmission from diffuse
  // and specular.
  float diffuse_weight, final_transmission, specular_weight;
};

// The lobes in Cycles' order: diffuse, sheen, specular, transmission, clearcoat (the order
// decides which closure is dropped beyond kMaxClosures).
void Surface::add_principled(const PrincipledInputs& in, Rgb weight) {
  const Vec3f N = node_normal(in.normal);
  const float eta = std::max(in.ior, 1e-5f);
  const float ior = frame_.backfacing ? 1.f / eta : eta;
  const float final_transmission = saturate(in.transmission) * (1.f - saturate(in.metallic));
  const PrincipledCommon p{in,
                           weight,
                           N,
                           frame_.I,
                           principled_tangent(in, N),
                           ior,
                           fresnel_dielectric_cos(dot(N, frame_.I), ior),
                           (1.f - saturate(in.metallic)) * (1.f - saturate(in.transmission)),
                           final_transmission,
                           1.f - final_transmission};
  add_principled_diffuse(p);
  add_principled_sheen(p);
  add_principled_specular(p);
  add_principled_transmission(p);
  add_principled_clearcoat(p);
}

// Diffuse. Subsurface scattering renders as its diffuse limit: the Principled diffuse closure
// (Lambert and retro-reflection) of the subsurface-mixed colour, which is what Cycles' BSSRDF
// setup makes when the radius is below BSSRDF_MIN_RADIUS (bssrdf.h bssrdf_setup), and what
// Cycles renders after a diffuse bounce (PATH_RAY_DIFFUSE_ANCESTOR).
void Surface::add_principled_diffuse(const PrincipledCommon& p) {
  const PrincipledInputs& in = p.in;
  const Rgb mixed_ss_base =
      in.subsurface_color * in.subsurface + in.base_color * (1.f - in.subsurface);
  if (!(std::abs(average(mixed_ss_base)) > kClosureWeightCutoff)) return;
  Rgb diffuse{};
  if (in.subsurface <= kClosureWeightCutoff && p.diffuse_weight > kClosureWeightCutoff)
    diffuse = p.weight * in.base_color * p.diffuse_weight;
  else if (in.subsurface > kClosureWeightCutoff)
    diffuse = p.weight * mixed_ss_base * p.diffuse_weight;
  if (Closure* c = allocate(ClosureType::kPrincipledDiffuse, diffuse, p.N))
    c->roughness = in.roughness;
}

// Sheen, tinted towards the base colour's hue (luminance-normalised, linear_rgb_to_gray with
// Rec. 709 weights).
void Surface::add_principled_sheen(const PrincipledCommon& p) {
  const PrincipledInputs& in = p.in;
  if (!(p.diffuse_weight > kClosureWeightCutoff && in.sheen > kClosureWeightCutoff)) return;
  const Rgb base = in.base_color;
  const float lum = luminance(base);
  const Rgb tint = lum > 0.f ? base / lum : Rgb{1.f, 1.f, 1.f};
  const Rgb sheen_color = Rgb{1.f, 1.f, 1.f} * (1.f - in.sheen_tint) + tint * in.sheen_tint;
  if (Closure* c = allocate(ClosureType::kPrincipledSheen,
                            p.weight * sheen_color * (in.sheen * p.diffuse_weight), p.N))
    c->sample_weight *= principled_sheen_average(p.N, p.I);
}

// Specular reflection: the index whose F0 is 0.08 specular, anisotropy stretching alpha along
// the tangent, and cspec0 between the (tinted) dielectric F0 and the base colour by metallic,
// the tint normalised by Cycles' "luminance approx." 0.3 r + 0.6 g + 0.1 b.
void Surface::add_principled_specular(const PrincipledCommon& p) {
  const PrincipledInputs& in = p.in;
  if (!(p.specular_weight > kClosureWeightCutoff &&
        (in.specular > kClosureWeightCutoff || in.metallic > kClosureWeightCutoff)))
    return;
  const bool single = in.distribution != Distribution::kMultiGgx || in.roughness <= 0.075f;
  Closure* c = allocate(single ? ClosureType::kMicrofacetReflect : ClosureType::kMultiGgxReflect,
                        p.weight * p.specular_weight, p.N);
  if (!c) return;
  const Rgb base = in.base_color;
  const float spec_ior = 2.f / (1.f - safe_sqrt(0.08f * in.specular)) - 1.f;
  const float aspect = safe_sqrt(1.f - in.anisotropic * 0.9f);
  const float r2 = in.roughness * in.roughness;
  const float cdlum = 0.3f * base.x + 0.6f * base.y + 0.1f * base.z;
  const Rgb tint = cdlum > 0.f ? base / cdlum : Rgb{1.f, 1.f, 1.f};
  const Rgb tmp_col = Rgb{1.f, 1.f, 1.f} * (1.f - in.specular_tint) + tint * in.specular_tint;
  const Rgb cspec0 = tmp_col * (in.specular * 0.08f * (1.f - in.metallic)) + base * in.metallic;
  c->microfacet =
      microfacet(r2 / aspect, r2 * aspect, spec_ior, p.T, cspec0, base, FresnelMode::kPrincipled);
  if (single) {
    single_scatter_setup(*c);
    scale_by_fresnel(*c, p.I);
  } else {  // bsdf_microfacet_multi_ggx_fresnel_setup: the Fresnel weight before saturating
    scale_by_fresnel(*c, p.I);
    multi_scatter_setup(*c);
  }
}

// Transmission: a glass of the base colour, its reflection tinted by Specular Tint; split into
// reflection and refraction by the Fresnel factor unless multiscatter GGX makes one glass closure.
void Surface::add_principled_transmission(const PrincipledCommon& p) {
  const PrincipledInputs& in = p.in;
  if (!(p.final_transmission > kClosureWeightCutoff)) return;
  const Rgb base = in.base_color;
  const Rgb glass_weight = p.weight * p.final_transmission;
  const Rgb cspec0 = base * in.specular_tint + Rgb{1.f, 1.f, 1.f} * (1.f - in.specular_tint);
  if (in.roughness <= 5e-2f || in.distribution != Distribution::kMultiGgx) {
    const float refl_roughness = in.roughness;
    if (Closure* c = allocate(ClosureType::kMicrofacetReflect, glass_weight * p.fresnel, p.N)) {
      const float a = refl_roughness * refl_roughness;
      c->microfacet = microfacet(a, a, p.ior, {}, cspec0, base, FresnelMode::kPrincipled);
      single_scatter_setup(*c);
      scale_by_fresnel(*c, p.I);
    }
    // The 1e-4 floor keeps MNEE from a null closure (svm_closure.h).
    const float refraction_fresnel = std::max(0.0001f, 1.f - p.fresnel);
    if (Closure* c = allocate(ClosureType::kMicrofacetRefract,
                              base * glass_weight * refraction_fresnel, p.N)) {
      // Transmission Roughness counts only with the GGX distribution.
      const float rough = in.distribution != Distribution::kMultiGgx
                              ? 1.f - (1.f - refl_roughness) * (1.f - in.transmission_roughness)
                              : refl_roughness;
      c->microfacet =
          microfacet(rough * rough, rough * rough, p.ior, {}, {}, {}, FresnelMode::kNone);
      single_scatter_setup(*c);
    }
  } else if (Closure* c = allocate(ClosureType::kMultiGgxGlass, glass_weight, p.N)) {
    const float a = in.roughness * in.roughness;
    c->microfacet = microfacet(a, a, p.ior, {}, cspec0, base, FresnelMode::kPrincipled);
    multi_scatter_setup(*c);
    scale_by_fresnel(*c, p.I);
  }
}

// Clearcoat: GTR1 with its own normal, F0 0.04 (ior 1.5), at full weight.
void Surface::add_principled_clearcoat(const PrincipledCommon& p) {
  const PrincipledInputs& in = p.in;
  if (!(in.clearcoat > kClosureWeightCutoff)) return;
  if (Closure* c =
          allocate(ClosureType::kMicrofacetReflect, p.weight, node_normal(in.clearcoat_normal))) {
    const float a = in.clearcoat_roughness * in.clearcoat_roughness;
    c->microfacet = microfacet(a, a, 1.5f, {}, {0.04f, 0.04f, 0.04f}, {}, FresnelMode::kClearcoat);
    c->microfacet.clearcoat = in.clearcoat;
    single_scatter_setup(*c);
    scale_by_fresnel(*c, p.I);
  }
}

void Surface::add_diffuse(Rgb color, float roughness, Vec3f normal, Rgb weight) {
  Closure* c = allocate(ClosureType::kDiffuse, color * weight, node_normal(normal));
  if (c && roughness != 0.f) oren_nayar_setup(*c, roughness);
}

void Surface::add_glossy(Distribution distribution, Rgb color, float roughness, Vec3f normal,
                         Rgb weight) {
  const Vec3f N = node_normal(normal);
  const float alpha = roughness * roughness;
  // GlossyBsdfNode::simplify_settings: an unlinked roughness <= 1e-4 is Sharp (with Filter
  // Glossy 0; otherwise GGX at alpha 0, which is the same mirror).
  if (distribution == Distribution::kSharp || roughness <= 1e-4f) {
    if (Closure* c = allocate(ClosureType::kSharpReflection, color * weight, N))
      c->microfacet = microfacet(0.f, 0.f, 1.f, {}, {}, {}, FresnelMode::kNone);
    return;
  }
  if (distribution == Distribution::kMultiGgx) {
    if (Closure* c = allocate(ClosureType::kMultiGgxReflect, color * weight, N)) {
      c->microfacet = microfacet(alpha, alpha, 1.f, {}, {}, color, FresnelMode::kNone);
      multi_scatter_setup(*c);
    }
    return;
  }
  // Ashikhmin-Shirley renders as GGX (docs/blender.md, "Blender materials").
  if (Closure* c = allocate(ClosureType::kMicrofacetReflect, color * weight, N)) {
    c->microfacet =
        microfacet(alpha, alpha, 1.f, {}, {}, {}, FresnelMode::kNone,
                   distribution == Distribution::kBeckmann ? MicrofacetDistribution::kBeckmann
                                                           : MicrofacetDistribution::kGgx);
    single_scatter_setup(*c);
  }
}

void Surface::add_glass(Distribution distribution, Rgb color, float roughness, float ior,
                        Vec3f normal, Rgb weight) {
  const Vec3f N = node_normal(normal);
  float eta = std::max(ior, 1e-5f);
  eta = frame_.backfacing ? 1.f / eta : eta;
  const float alpha = roughness * roughness;
  const Rgb w = color * weight;
  if (distribution == Distribution::kMultiGgx && roughness > 1e-4f) {
    if (Closure* c = allocate(ClosureType::kMultiGgxGlass, w, N)) {
      c->microfacet = microfacet(alpha, alpha, eta, {}, {}, color, FresnelMode::kNone);
      multi_scatter_setup(*c);
    }
    return;
  }
  // Reflection and refraction split by the Fresnel factor at the shading normal.
  const float fresnel = fresnel_dielectric_cos(dot(N, frame_.I), eta);
  const bool sharp = distribution == Distribution::kSharp || roughness <= 1e-4f;
  const MicrofacetDistribution d = distribution == Distribution::kBeckmann
                                       ? MicrofacetDistribution::kBeckmann
                                       : MicrofacetDistribution::kGgx;
  if (Closure* c = allocate(sharp ? ClosureType::kSharpReflection : ClosureType::kMicrofacetReflect,
                            w * fresnel, N)) {
    c->microfacet = microfacet(alpha, alpha, eta, {}, {}, {}, FresnelMode::kNone, d);
    single_scatter_setup(*c);
  }
  if (Closure* c = allocate(sharp ? ClosureType::kSharpRefraction : ClosureType::kMicrofacetRefract,
                            w * std::max(0.0001f, 1.f - fresnel), N)) {
    c->microfacet = microfacet(alpha, alpha, eta, {}, {}, {}, FresnelMode::kNone, d);
    single_scatter_setup(*c);
  }
}

}  // namespace fb
