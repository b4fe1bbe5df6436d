// One closure of a surface: a BSDF lobe with its weight, as Cycles 3.4 stores it in ShaderData
// (kernel/types.h ShaderClosure, kernel/closure/alloc.h bsdf_alloc). Closures work in render
// space, as Cycles' do: `I` is the unit direction back towards where the ray came from (sd->I),
// `omega_in` the unit direction light arrives from, `N` the closure's shading normal on I's side.
//
// eval() returns f(I, omega_in) |N.omega_in| (Cycles' "eval" carries the cosine) and the
// solid-angle pdf with which the closure's sample() draws omega_in; sample() draws omega_in and
// returns the same pair for it. A singular closure (a perfect mirror or refraction, or a
// microfacet lobe narrower than Cycles resolves: alpha_x alpha_y <= 1e-7) evaluates to zero and
// samples with `singular` set: then `eval` is the weight f |cos| / pdf of the delta lobe and
// `pdf` is 1 (Cycles returns eval = pdf = 1e6 "for MIS" instead).
#pragma once

#include <cstdint>

#include <filmback/vec.h>

namespace fb {

// Cycles' CLOSURE_WEIGHT_CUTOFF (kernel/svm/types.h): closures whose average weight is below it
// are not allocated (bsdf_alloc), and node inputs below it switch their lobes off.
inline constexpr float kClosureWeightCutoff = 1e-5f;

enum class ClosureType : uint8_t {
  kDiffuse,            // CLOSURE_BSDF_DIFFUSE_ID, bsdf_diffuse.h
  kOrenNayar,          // CLOSURE_BSDF_OREN_NAYAR_ID, bsdf_oren_nayar.h
  kPrincipledDiffuse,  // CLOSURE_BSDF_PRINCIPLED_DIFFUSE_ID (FULL), bsdf_principled_diffuse.h
  kPrincipledSheen,    // CLOSURE_BSDF_PRINCIPLED_SHEEN_ID, bsdf_principled_sheen.h
  kSharpReflection,    // CLOSURE_BSDF_REFLECTION_ID, bsdf_reflection.h
  kSharpRefraction,    // CLOSURE_BSDF_REFRACTION_ID, bsdf_refraction.h
  kMicrofacetReflect,  // CLOSURE_BSDF_MICROFACET_{GGX,GGX_FRESNEL,GGX_CLEARCOAT,BECKMANN}_ID
  kMicrofacetRefract,  // CLOSURE_BSDF_MICROFACET_{GGX,BECKMANN}_REFRACTION_ID
  kMultiGgxReflect,    // CLOSURE_BSDF_MICROFACET_MULTI_GGX{,_FRESNEL}_ID, bsdf_microfacet_multi.h
  kMultiGgxGlass,      // CLOSURE_BSDF_MICROFACET_MULTI_GGX_GLASS{,_FRESNEL}_ID
};

// What Cycles 3.4's colour passes sort closures by (kernel/closure/bsdf.h and types.h,
// CLOSURE_IS_BSDF_DIFFUSE / _GLOSSY / _TRANSMISSION; surface_shader_diffuse, _glossy and
// _transmission sum the weights of one kind into DiffCol, GlossCol and TransCol).
enum class ClosureKind : uint8_t { kDiffuse, kGlossy, kTransmission };

// Which Fresnel factor a microfacet lobe applies (bsdf_microfacet.h reflection_color()).
enum class FresnelMode : uint8_t {
  kNone,        // white: the Glossy and Glass nodes, whose Fresnel is in their weights
  kPrincipled,  // interpolate_fresnel_color() between cspec0 and white (the Principled BSDF)
  kClearcoat,   // the same with cspec0 0.04, times 0.25 clearcoat, GTR1 distribution
};

enum class MicrofacetDistribution : uint8_t { kGgx, kBeckmann };

struct MicrofacetParams {
  float alpha_x, alpha_y;  // along T and along N x T; equal for isotropic lobes
  float ior;               // relative index across the surface, seen from I's side
  Vec3f T;                 // unit tangent, perpendicular to N (anisotropic lobes only)
  Rgb cspec0;              // Fresnel colour at normal incidence (FresnelMode::kPrincipled)
  Rgb color;               // multiscatter lobes: the colour of the second and later bounces
  float clearcoat;         // FresnelMode::kClearcoat
  MicrofacetDistribution distribution;
  FresnelMode fresnel;
};

struct Closure {
  Closure() : roughness(0.f) {}  // the union's members have no default constructor in common

  ClosureType type = ClosureType::kDiffuse;
  Rgb weight;                 // the node's colour times its mix weight
  float sample_weight = 0.f;  // how often sample() picks it, relative to the others
  Vec3f N;                    // unit shading normal on I's side
  union {
    float roughness;  // kPrincipledDiffuse: Burley's retro-reflection roughness
    struct {
      float a, b;  // kOrenNayar: Fujii's A and B (bsdf_oren_nayar_setup)
    } oren_nayar;
    MicrofacetParams microfacet;  // kSharp*, kMicrofacet*, kMultiGgx*
  };

  bool is_diffuse() const { return type <= ClosureType::kPrincipledSheen; }
  // Cycles' ranges of closure ids: the multiscatter glass, one closure for reflection and
  // refraction, counts as transmission there.
  ClosureKind kind() const {
    if (is_diffuse()) return ClosureKind::kDiffuse;
    switch (type) {
      case ClosureType::kSharpRefraction:
      case ClosureType::kMicrofacetRefract:
      case ClosureType::kMultiGgxGlass:
        return ClosureKind::kTransmission;
      default:
        return ClosureKind::kGlossy;
    }
  }
};

// What a closure sees of the hit besides its own parameters.
struct ClosureContext {
  Vec3f I;   // unit, towards the viewer (sd->I)
  Vec3f Ng;  // geometric normal on I's side (sd->Ng)
  Vec3f N;   // interpolated normal before bump and normal maps, on I's side (sd->N)
};

struct ClosureSample {
  Vec3f omega_in;
  Rgb eval;         // f |cos| (singular: f |cos| / pdf)
  float pdf = 0.f;  // 0: no sample
  bool singular = false;
};

// Cycles' eval and sample for every closure type (closure.cpp dispatches to the bsdf_*.h files).
// `u` is the direction's random pair; multiscatter lobes draw their random walk from a hash of
// the directions and `u` (bsdf_microfacet_multi.h).
Rgb closure_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in, float& pdf);
bool closure_sample(const Closure& c, const ClosureContext& ctx, Vec2f u, ClosureSample& s);

}  // namespace fb
