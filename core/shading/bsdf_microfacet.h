// Cycles 3.4's single-scattering microfacet closures (kernel/closure/bsdf_microfacet.h, from
// OSL), reflection and refraction, GGX and Beckmann:
//  - Walter, Marschner, Li and Torrance 2007, "Microfacet Models for Refraction through Rough
//    Surfaces": D (eqs. 25 and 33), the reflection and refraction BSDFs (eqs. 20 and 21), the
//    half vectors (eqs. 13 and 16), and Smith's *separable* G = G1(I) G1(omega_in) (eqs. 23,
//    27, 34), which is what Cycles 3.4 uses (not the height-correlated form);
//  - anisotropic GGX D and G1 with the projected roughness (Heitz 2014, "Understanding the
//    Masking-Shadowing Function in Microfacet-Based BRDFs"), along the tangent T;
//  - sampling of visible normals by stretching (Heitz and d'Eon 2014, "Importance Sampling
//    Microfacet-Based BSDFs using the Distribution of Visible Normals"), with Jakob 2014's
//    Beckmann slope inversion ("An Improved Visible Normal Sampling Routine for the Beckmann
//    Distribution", as Cycles' GPU kernels do; its CPU kernels read the same inverse from a table);
//  - Beckmann's G1 is Walter's rational approximation (eq. 27), as in Cycles;
//  - the Principled BSDF's Fresnel colour (interpolate_fresnel_color) and the clearcoat lobe,
//    Burley 2012's GTR1 distribution with G fixed at alpha 0.25 and 0.25 clearcoat Fresnel.
//
// Lobes with alpha_x alpha_y <= 1e-7 are singular (a mirror or a sharp refraction).
// Refraction does not scale radiance by 1/eta^2 (Cycles does not: a sampled refraction carries
// weight G1(omega_in)).
#pragma once

#include "core/shading/closure.h"

namespace fb {

// Cycles' threshold below which a microfacet lobe is a delta lobe.
inline bool microfacet_singular(const MicrofacetParams& m) {
  return m.alpha_x * m.alpha_y <= 1e-7f;
}

Rgb microfacet_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in, float& pdf);
bool microfacet_sample(const Closure& c, const ClosureContext& ctx, Vec2f u, ClosureSample& s);

// The perfectly specular closures of the Glossy and Glass nodes' Sharp distribution
// (bsdf_reflection.h, bsdf_refraction.h): white, no Fresnel (the Glass node weights them).
bool sharp_reflection_sample(const Closure& c, const ClosureContext& ctx, ClosureSample& s);
bool sharp_refraction_sample(const Closure& c, const ClosureContext& ctx, ClosureSample& s);

}  // namespace fb
