#include "core/shading/surface.h"

#include <algorithm>
#include <cmath>

namespace fb {

void Surface::begin(const ShadingFrame& frame) {
  frame_ = frame;
  gltf_.reset();
}

void Surface::add_gltf(const GltfSurfaceParams& p) {
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

// Until Cycles' closures land, Blender's nodes render through the glTF model's lobes: the first
// node reached, at full weight (a placeholder for the pipeline, not Cycles' model).
void Surface::add_principled(const PrincipledInputs& in, Rgb weight) {
  if (gltf_) return;
  add_gltf({in.base_color * weight, in.metallic, in.roughness, in.transmission, in.ior,
            std::clamp(2.f * in.specular, 0.f, 1.f), in.normal});
}

void Surface::add_diffuse(Rgb color, float, Vec3f normal, Rgb weight) {
  if (!gltf_) add_gltf({color * weight, 0.f, 1.f, 0.f, 1.5f, 0.f, normal});
}

void Surface::add_glossy(Distribution, Rgb color, float roughness, Vec3f normal, Rgb weight) {
  if (!gltf_) add_gltf({color * weight, 1.f, roughness, 0.f, 1.5f, 1.f, normal});
}

void Surface::add_glass(Distribution, Rgb color, float roughness, float ior, Vec3f normal,
                        Rgb weight) {
  if (!gltf_) add_gltf({color * weight, 0.f, roughness, 1.f, ior, 1.f, normal});
}

Rgb Surface::eval(Vec3f wi_world, float& pdf) const {
  pdf = 0.f;
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
