// A Blender material's shader graph (core/scene/shader_graph.h) evaluated at a hit, as Cycles'
// SVM evaluates the same nodes (intern/cycles/kernel/svm/svm_closure.h, and the graph rewrites of
// intern/cycles/scene/shader_nodes.cpp): the Mix and Add shaders' weights multiplied down to each
// BSDF node, whose closures join the hit's Surface with that weight; Emission nodes and the
// Principled BSDF's emission summed into the hit's emission; Transparent nodes and the Principled
// BSDF's alpha summed into a transparency that the host turns into coverage (alpha), so that the
// rest is scaled by 1 / (1 - transparency) where the hit is kept.
#pragma once

#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

#include "core/scene/shader_graph.h"
#include "core/shading/surface.h"
#include "core/texture/texture_images.h"

namespace fb {

struct SurfacePoint;

class GraphShader {
 public:
  GraphShader(const ShaderGraph& graph, const TextureImages& images)
      : graph_(graph), images_(images) {}

  // The hit's principal fields (base colour and the like, for integrators that show them) and its
  // emission; hit.shading_normal must hold the interpolated normal (front side) and gets the
  // first normal-mapped BSDF's normal.
  void shade(const SurfacePoint& point, fb_hit& hit) const;
  // The closures, for a ray arriving as `frame` says, scaled for the hit being kept (coverage).
  void build(const SurfacePoint& point, const ShadingFrame& frame, Surface& surface) const;
  // Radiance leaving the point (both faces, as Cycles' emission), for a kept hit.
  Rgb emission(const SurfacePoint& point) const;
  // 1 - the summed weight of Transparent closures (their colour's average), in [0, 1].
  float coverage(const SurfacePoint& point) const;

  // What importers and the render need without a hit: whether any node can be transparent, and
  // an upper bound of the emitted radiance (textures counted as 1) for choosing among lights.
  static bool can_be_transparent(const ShaderGraph& graph);
  static Rgb emission_bound(const ShaderGraph& graph);

 private:
  // Calls visit(node, weight) for every BSDF, Emission and Transparent node reached from the
  // output, with the product of the mix weights above it.
  template <typename Visit>
  void walk(const SurfacePoint& point, Visit&& visit) const;
  template <typename Visit>
  void walk(uint32_t node, Rgb weight, const SurfacePoint& point, Visit& visit, int depth) const;

  // An input's value at the point: constants, texture lookups, Cycles' implicit conversions.
  Vec3f colour(const ShaderInput& in, const SurfacePoint& point) const;
  float number(const ShaderInput& in, const SurfacePoint& point) const;
  // A normal input's normal (front side): unset is the interpolated normal `smooth`; a Normal Map
  // node bends it (Cycles' svm_node_normal_map).
  Vec3f normal(const ShaderInput& in, const SurfacePoint& point, Vec3f smooth) const;
  std::array<float, 4> texel(uint32_t texture, const SurfacePoint& point) const;

  const ShaderGraph& graph_;
  const TextureImages& images_;
};

}  // namespace fb
