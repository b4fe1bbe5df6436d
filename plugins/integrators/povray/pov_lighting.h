// POV-Ray 3.7's classic lighting terms, one function each, as its renderer computes them
// (source/core/render/trace.cpp: ComputeDiffuseColour, ComputePhongColour, ComputeSpecularColour,
// ComputeReflectivity, ComputeMetallic, ComputeFresnel, TraceRefractionRay; docs/pov.md "The
// povray integrator"). Vectors are unit; `view` is the direction the ray travels (towards the
// surface), `to_light` points from the surface to the light, `normal` faces the viewer.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

namespace fb::pov_lighting {

// POV-Ray's EPSILON: lights this close to the surface's horizon light nothing.
constexpr float kHorizonCosine = 1e-5f;

// A finish with only `diffuse`: no ambient, highlight, reflection or transparency, and POV-Ray's
// defaults for the rest (brilliance 1, phong_size 40, roughness 0.05, falloff 1, ior 1).
constexpr fb_pov_finish diffuse_finish(float diffuse) {
  fb_pov_finish f{};
  f.present = 1;
  f.pigment[0] = f.pigment[1] = f.pigment[2] = 1.f;
  f.pigment_scale = 1.f, f.coverage = 1.f;
  f.diffuse = diffuse, f.brilliance = 1.f;
  f.phong_size = 40.f, f.roughness = 0.05f;
  f.reflection_falloff = 1.f, f.reflection_exponent = 1.f;
  f.ior = 1.f;
  return f;
}

inline Rgb rgb(const float c[3]) {
  return Rgb(c[0], c[1], c[2]);
}

// Each channel to the power `exponent`, negative ones taken as 0 (a reflection's `exponent`, a
// colour's gamma).
inline Rgb raised(Rgb c, float exponent) {
  if (exponent == 1.f) return c;
  return {std::pow(std::max(c.x, 0.f), exponent), std::pow(std::max(c.y, 0.f), exponent),
          std::pow(std::max(c.z, 0.f), exponent)};
}

// The pigment's colour at the hit: the host's base colour divided by what the importer scaled the
// pigment by. Where that scale is 0 (a finish without diffuse), the host's emission, which is the
// pigment at the hit times ambient + emission (docs/pov.md, "Finishes and interiors"), divided by
// them; the pigment's constant colour in a channel where they are 0.
inline Rgb pigment_at_hit(const fb_pov_finish& f, const fb_hit& hit) {
  if (f.pigment_scale > 0.f) return rgb(hit.base_color) / f.pigment_scale;
  float pigment[3];
  for (int c = 0; c < 3; ++c) {
    const float glow = f.ambient[c] + f.emission[c];
    pigment[c] = glow > 0.f ? hit.emission[c] / glow : f.pigment[c];
  }
  return rgb(pigment);
}

// What a hit lets through of what lies behind it: filter * pigment + transmit (POV-Ray's
// TransmittedColour), less the transmit the host's coverage already passed by (a hit on a
// blended pigment is found with probability `coverage`; what the caller adds is divided by it).
inline Rgb passed_through(const fb_pov_finish& f, Rgb pigment) {
  return pigment * f.filter + Rgb(1.f, 1.f, 1.f) * (f.transmit - (1.f - f.coverage));
}

// Diffuse: diffuse * cos(theta)^brilliance * opacity, times the pigment and the light.
inline Rgb diffuse(const fb_pov_finish& f, float cos_light, float opacity, Rgb pigment, Rgb light) {
  if (!(cos_light > 0.f) || f.diffuse == 0.f) return {};
  const float shape = f.brilliance != 1.f ? std::pow(cos_light, f.brilliance) : cos_light;
  return pigment * light * (shape * f.diffuse * opacity);
}

// The highlight's colour: the light's, or with `metallic` m, tinted towards the pigment by
// 1 + m (1 - F) (pigment - 1), F POV-Ray's empirical Fresnel curve of the angle to the light.
inline Rgb metallic_tint(float metallic, float cos_angle, Rgb pigment) {
  if (metallic == 0.f) return {1.f, 1.f, 1.f};
  const float x = std::abs(std::acos(std::clamp(cos_angle, -1.f, 1.f))) / (0.5f * 3.14159265f);
  const float fresnel =
      std::clamp(0.014567225f / ((x - 1.12f) * (x - 1.12f)) - 0.011612903f, 0.f, 1.f);
  return Rgb(1.f, 1.f, 1.f) + (pigment - Rgb(1.f, 1.f, 1.f)) * (metallic * (1.f - fresnel));
}

// Phong: phong * cos(angle between the mirrored view and the light)^phong_size.
inline Rgb phong(const fb_pov_finish& f, Vec3f view, Vec3f normal, Vec3f to_light, Rgb pigment,
                 Rgb light) {
  if (!(f.phong > 0.f)) return {};
  const Vec3f mirrored = view - normal * (2.f * dot(view, normal));
  const float c = dot(mirrored, to_light);
  // POV-Ray skips the tiny values of very wide lobes (its "rgs" cut-off).
  if (!(c > 0.f) || (f.phong_size >= 60.f && c <= 0.0008f)) return {};
  return light * metallic_tint(f.metallic, dot(normal, to_light), pigment) *
         (f.phong * std::pow(c, f.phong_size));
}

// Specular: specular * cos(angle between the normal and the half vector)^(1 / roughness).
inline Rgb specular(const fb_pov_finish& f, Vec3f view, Vec3f normal, Vec3f to_light, Rgb pigment,
                    Rgb light) {
  if (!(f.specular > 0.f)) return {};
  const Vec3f half = to_light - view;
  const float half_length = std::sqrt(dot(half, half));
  if (!(half_length > 0.f)) return {};
  const float c = dot(half, normal) / half_length;
  if (!(c > 0.f)) return {};
  const float exponent = 1.f / std::max(f.roughness, 1e-6f);
  return light * metallic_tint(f.metallic, dot(normal, to_light), pigment) *
         (f.specular * std::pow(c, exponent));
}

// Unpolarised Fresnel reflectance for the relative index `eta` (n2 / n1) at cos_i, as POV-Ray's
// ComputeFresnel writes it (Cook and Torrance's form); 1 past the critical angle.
inline float fresnel(float cos_i, float eta) {
  const float sqx = eta * eta + cos_i * cos_i - 1.f;
  if (!(sqx > 0.f)) return 1.f;
  const float g = std::sqrt(sqx);
  const float a = (g - cos_i) / (g + cos_i);
  const float b = (cos_i * (g + cos_i) - 1.f) / (cos_i * (g - cos_i) + 1.f);
  return std::clamp(0.5f * a * a * (1.f + b * b), 0.f, 1.f);
}

// How much of the reflected ray a surface adds: between reflection_min (facing) and
// reflection_max (grazing) by (1 - cos)^falloff, or by Fresnel's law with `fresnel`; then tinted
// by the pigment when the reflection is metallic. `eta` is the relative index at the hit.
inline Rgb reflectivity(const fb_pov_finish& f, float cos_i, float eta, Rgb pigment) {
  const Rgb lo = rgb(f.reflection_min), hi = rgb(f.reflection_max);
  Rgb r;
  if (f.reflection_fresnel) {
    const float k = fresnel(cos_i, eta);
    r = hi * k + lo * (1.f - k);
  } else {
    const float k = std::pow(std::max(1.f - cos_i, 0.f), f.reflection_falloff);
    r = hi * k + lo * (1.f - k);
  }
  if (f.reflection_metallic != 0.f) r *= metallic_tint(f.reflection_metallic, cos_i, pigment);
  return r;
}

// The direction a ray along `view` takes into a medium of relative index `eta` (n2 / n1) through a
// surface of (viewer-facing) normal `normal` (Heckbert's method); none on total internal
// reflection.
inline std::optional<Vec3f> refracted(Vec3f view, Vec3f normal, float eta) {
  const float ratio = 1.f / eta;  // POV-Ray's ior: n1 / n2
  const float n = -dot(view, normal);
  const float t = 1.f + ratio * ratio * (n * n - 1.f);
  if (t < 0.f) return std::nullopt;
  const Vec3f d = view * ratio + normal * (ratio * n - std::sqrt(t));
  return d / std::sqrt(dot(d, d));
}

}  // namespace fb::pov_lighting
