// Cycles 3.4's multiple-scattering GGX closures (kernel/closure/bsdf_microfacet_multi.h and
// bsdf_microfacet_multi_impl.h): Heitz, Hanika, d'Heon and Dachsbacher 2016, "Multiple-Scattering
// Microfacet BSDFs with the Smith Model". A light path is a random walk over the heights and
// normals of the Smith microsurface (uniform height distribution, GGX visible normals), up to
// ten bounces; the glossy walk reflects at every microfacet, the glass walk reflects or refracts
// by the dielectric Fresnel. Evaluation adds the single-scattering term analytically and the
// walk's next-event estimates towards omega_in; sampling returns the walk's exit direction with
// its throughput as the weight. The pdf is not the walk's density but Cycles' approximation, the
// single-scattering pdf plus a cosine lobe for the missing energy (mf_ggx_pdf, mf_glass_pdf): with
// the walk's throughput as the sample weight the estimate stays unbiased.
//
// Cycles draws the walk from a per-path LCG, so its evaluation is stochastic (its expectation is
// the BSDF). Here the same LCG (Cycles' kernel/sample/lcg.h constants) is seeded from a hash of
// the two directions for evaluation and of I and the sample's random pair for sampling: the same
// arguments always give the same value, a surface can be evaluated twice and agree, and across
// directions the values average to the BSDF as Cycles' do.
//
// Kept as Cycles 3.4 has them, because the renders must agree: the Fresnel colour of the first
// bounce is taken at the half vector of I and omega_in in evaluation; the glossy evaluation
// applies the accumulated colour twice to the later bounces ("phase * throughput" multiplied by
// throughput again); the glass evaluation with Fresnel replaces the analytic single-scattering term
// by the walk's first bounce.
#pragma once

#include "core/shading/closure.h"

namespace fb {

Rgb multi_ggx_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in, float& pdf);
bool multi_ggx_sample(const Closure& c, const ClosureContext& ctx, Vec2f u, ClosureSample& s);

}  // namespace fb
