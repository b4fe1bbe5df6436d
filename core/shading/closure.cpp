#include "core/shading/closure.h"

#include "core/shading/bsdf_diffuse.h"
#include "core/shading/bsdf_microfacet.h"
#include "core/shading/bsdf_microfacet_multi.h"
#include "core/shading/bsdf_oren_nayar.h"
#include "core/shading/bsdf_principled_diffuse.h"
#include "core/shading/bsdf_principled_sheen.h"

namespace fb {

Rgb closure_eval(const Closure& c, const ClosureContext& ctx, Vec3f omega_in, float& pdf) {
  pdf = 0.f;
  switch (c.type) {
    case ClosureType::kDiffuse:
      return diffuse_eval(c, omega_in, pdf);
    case ClosureType::kOrenNayar:
      return oren_nayar_eval(c, ctx, omega_in, pdf);
    case ClosureType::kPrincipledDiffuse:
      return principled_diffuse_eval(c, ctx, omega_in, pdf);
    case ClosureType::kPrincipledSheen:
      return principled_sheen_eval(c, ctx, omega_in, pdf);
    case ClosureType::kSharpReflection:
    case ClosureType::kSharpRefraction:
      return {};  // delta lobes: only sampling finds them
    case ClosureType::kMicrofacetReflect:
    case ClosureType::kMicrofacetRefract:
      return microfacet_eval(c, ctx, omega_in, pdf);
    case ClosureType::kMultiGgxReflect:
    case ClosureType::kMultiGgxGlass:
      return multi_ggx_eval(c, ctx, omega_in, pdf);
  }
  return {};
}

bool closure_sample(const Closure& c, const ClosureContext& ctx, Vec2f u, ClosureSample& s) {
  s = {};
  switch (c.type) {
    case ClosureType::kDiffuse:
      return diffuse_sample(c, ctx, u, s);
    case ClosureType::kOrenNayar:
      return oren_nayar_sample(c, ctx, u, s);
    case ClosureType::kPrincipledDiffuse:
      return principled_diffuse_sample(c, ctx, u, s);
    case ClosureType::kPrincipledSheen:
      return principled_sheen_sample(c, ctx, u, s);
    case ClosureType::kSharpReflection:
      return sharp_reflection_sample(c, ctx, s);
    case ClosureType::kSharpRefraction:
      return sharp_refraction_sample(c, ctx, s);
    case ClosureType::kMicrofacetReflect:
    case ClosureType::kMicrofacetRefract:
      return microfacet_sample(c, ctx, u, s);
    case ClosureType::kMultiGgxReflect:
    case ClosureType::kMultiGgxGlass:
      return multi_ggx_sample(c, ctx, u, s);
  }
  return false;
}

}  // namespace fb
