#include "core/shading/surface.h"

#include <cmath>

#include "core/shading/fresnel.h"

namespace fb {

void Surface::begin(const ShadingFrame& frame) {
  frame_ = frame;
  gltf_.reset();
  count_ = 0;
}

void Surface::add_gltf(const GltfSurfaceParams& p) {
  count_ = 0;
  const Vec3f n = frame_.backfacing ? -p.normal : p.normal;
  const Frame local(ensure_valid_reflection(frame_.Ng, frame_.I, n));
  // Transmission makes the side matter: from the back face the ray leaves the material, so the
  // index ratio inverts.
  const float eta = p.transmission > 0.f && frame_.backfacing ? 1.f / p.ior : p.ior;
  gltf_.emplace(Gltf{local,
                     Bsdf({p.base_color, p.metallic, p.roughness, p.transmission, eta, p.specular,
                           local.to_local(frame_.N)}),
                     local.to_local(frame_.I)});
}

Rgb Surface::closure_weight(ClosureKind kind) const {
  if (gltf_) {
    switch (kind) {
      case ClosureKind::kDiffuse:
        return gltf_->bsdf.diffuse_weight();
      case ClosureKind::kGlossy:
        return gltf_->bsdf.glossy_weight();
      case ClosureKind::kTransmission:
        return gltf_->bsdf.transmission_weight();
    }
  }
  Rgb sum{};
  for (int i = 0; i < count_; ++i)
    if (closures_[i].kind() == kind) sum += closures_[i].weight;
  return sum;
}

Closure* Surface::allocate(ClosureType type, Rgb weight, Vec3f N) {
  weight = max(weight, Rgb{});
  const float sample_weight = std::abs(average(weight));
  // Written so that a non-finite average makes no closure, as bsdf_alloc is.
  if (!(sample_weight >= kClosureWeightCutoff) || !std::isfinite(sample_weight)) return nullptr;
  gltf_.reset();
  int slot = count_;
  if (count_ == kMaxClosures) {
    // Full: replace the lightest closure if the new one outweighs it. The caller may still
    // scale the sample weight down (Fresnel, sheen); the choice is made on the weight alone.
    slot = 0;
    for (int i = 1; i < count_; ++i)
      if (closures_[i].sample_weight < closures_[slot].sample_weight) slot = i;
    if (!(sample_weight > closures_[slot].sample_weight)) return nullptr;
  } else {
    ++count_;
  }
  Closure& c = closures_[slot];
  c.type = type;
  c.weight = weight;
  c.sample_weight = sample_weight;
  c.N = N;
  return &c;
}

Vec3f Surface::node_normal(Vec3f normal) const {
  Vec3f n = frame_.N;
  if (dot(normal, normal) > 0.f) n = frame_.backfacing ? -normal : normal;
  return ensure_valid_reflection(frame_.Ng, frame_.I, n);
}

bool Surface::reachable(const Closure& c, Vec3f wi) const {
  switch (c.type) {
    case ClosureType::kSharpRefraction:
    case ClosureType::kMicrofacetRefract:
    case ClosureType::kMultiGgxGlass:
      return true;  // Cycles' refraction sampling does not test the geometric normal
    default:
      return dot(frame_.Ng, wi) > 0.f;
  }
}

float Surface::bump_factor(const Closure& c, Vec3f wi) const {
  // bsdf.h bsdf_eval and bsdf_sample: the terminator term for diffuse closures whose normal was
  // bent away from the interpolated one.
  const bool bent = c.N.x != frame_.N.x || c.N.y != frame_.N.y || c.N.z != frame_.N.z;
  return c.is_diffuse() && bent ? bump_shadowing_term(frame_.N, c.N, wi) : 1.f;
}

Rgb Surface::accumulate(Vec3f wi, const Closure* skip, const Picking& picking,
                        float& weighted_pdf) const {
  Rgb f{};
  for (int i = 0; i < count_; ++i) {
    const Closure& c = closures_[i];
    if (&c == skip) continue;
    float pdf = 0.f;
    const Rgb e = closure_eval(c, context(), wi, pdf) * bump_factor(c, wi);
    if (pdf == 0.f) continue;
    f += e * c.weight;
    if (reachable(c, wi)) weighted_pdf += pdf * picking.weight(c);
  }
  return f;
}

Surface::Picking Surface::picking() const {
  float sum = 0.f;
  for (int i = 0; i < count_; ++i)
    sum += closures_[i].sample_weight;
  Picking p{0.f, sum};
  if (frame_.camera_ray && count_ > 1) {
    p.floor = 0.125f * sum;
    p.sum = 0.f;
    for (int i = 0; i < count_; ++i)
      p.sum += p.weight(closures_[i]);
  }
  return p;
}

Rgb Surface::eval(Vec3f wi_world, float& pdf) const {
  pdf = 0.f;
  if (count_ > 0) {
    const Picking picking = this->picking();
    float weighted_pdf = 0.f;
    const Rgb f = accumulate(wi_world, nullptr, picking, weighted_pdf);
    pdf = picking.sum > 0.f ? weighted_pdf / picking.sum : 0.f;
    return f;
  }
  if (!gltf_ || !(gltf_->wo.z > 0.f)) return {};
  const Vec3f wi = gltf_->frame.to_local(wi_world);
  // Light above the shading normal but below the flat facet (the terminator of a coarse mesh with
  // smooth normals) is evaluated, as Cycles does; BSDF sampling never goes there (sample()), so
  // its pdf is 0 and light sampling takes the whole weight.
  const bool reachable = consistent(wi_world, wi);
  if (!reachable && !(wi.z > 0.f)) return {};
  const Rgb f = gltf_->bsdf.eval(gltf_->wo, wi) * std::abs(wi.z);
  if (reachable) pdf = gltf_->bsdf.pdf(gltf_->wo, wi);
  return f;
}

bool Surface::sample(const float u[3], SurfaceSample& s) const {
  if (count_ > 0) {
    // surface_shader_bsdf_bssrdf_pick: u[0] picks by sample weight; (u[1], u[2]) draw the
    // direction (Cycles reuses the rescaled u[0] instead of a third number).
    const Picking picking = this->picking();
    const float sum = picking.sum;
    if (!(sum > 0.f)) return false;
    const float r = u[0] * sum;
    float partial = 0.f;
    int picked = count_ - 1;
    for (int i = 0; i < count_; ++i) {
      if (r < partial + picking.weight(closures_[i])) {
        picked = i;
        break;
      }
      partial += picking.weight(closures_[i]);
    }
    const Closure& c = closures_[picked];
    ClosureSample cs;
    if (!closure_sample(c, context(), {u[1], u[2]}, cs) || !(cs.pdf > 0.f)) return false;
    s.wi = cs.omega_in;
    s.transmission = dot(frame_.Ng, s.wi) < 0.f;
    s.delta = cs.singular;
    Rgb f = cs.eval * c.weight * bump_factor(c, s.wi);
    if (cs.singular) {
      // A delta lobe outweighs every other closure in its direction (Cycles' 1e6 pdf).
      s.pdf = picking.weight(c) / sum;
      s.weight = f / s.pdf;
    } else {
      float weighted_pdf = cs.pdf * picking.weight(c);
      f += accumulate(s.wi, &c, picking, weighted_pdf);
      s.pdf = weighted_pdf / sum;
      s.weight = f / s.pdf;
    }
    return is_finite(s.weight) && s.pdf > 0.f;
  }
  if (!gltf_ || !(gltf_->wo.z > 0.f)) return false;
  Bsdf::Sample b;
  if (!gltf_->bsdf.sample(gltf_->wo, u[0], {u[1], u[2]}, b)) return false;
  s.wi = gltf_->frame.to_world(b.wi);
  if (!consistent(s.wi, b.wi)) return false;
  s.weight = b.weight;
  s.pdf = b.pdf;
  s.delta = false;
  s.transmission = b.wi.z < 0.f;
  return true;
}

}  // namespace fb
