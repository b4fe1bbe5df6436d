// The inputs of Blender 3.4's shader nodes that become closures (Cycles' svm_closure.h), as the
// material graph evaluates them at a hit: textures applied, normals already normal-mapped, in
// render space and in fb_hit's orientation (the front side; Surface turns them to the side the
// ray arrived from, as Cycles turns sd->N). A zero normal is the node's unlinked Normal socket:
// the interpolated normal. Defaults are Blender 3.4's socket defaults.
#pragma once

#include <cstdint>

#include <filmback/vec.h>

#include "core/scene/shader_graph.h"

namespace fb {

// Principled BSDF (v1, Blender 3.4). Emission and Alpha are not closures: the caller handles
// them (Cycles adds an Emission and mixes a Transparent BSDF around the node,
// PrincipledBsdfNode::expand).
struct PrincipledInputs {
  Rgb base_color{0.8f, 0.8f, 0.8f};
  float subsurface = 0.f;
  Vec3f subsurface_radius{1.f, 0.2f, 0.1f};  // m
  Rgb subsurface_color{0.8f, 0.8f, 0.8f};
  float subsurface_ior = 1.4f;
  float subsurface_anisotropy = 0.f;
  float metallic = 0.f;
  float specular = 0.5f;
  float specular_tint = 0.f;
  float roughness = 0.5f;
  float anisotropic = 0.f;
  float anisotropic_rotation = 0.f;  // turns about the normal
  float sheen = 0.f;
  float sheen_tint = 0.5f;
  float clearcoat = 0.f;
  float clearcoat_roughness = 0.03f;
  float ior = 1.45f;
  float transmission = 0.f;
  float transmission_roughness = 0.f;
  Vec3f normal{};                                  // zero: the interpolated normal
  Vec3f clearcoat_normal{};                        // zero: the interpolated normal
  Vec3f tangent{};                                 // zero: see Surface::add_principled
  Distribution distribution = Distribution::kGgx;  // kGgx or kMultiGgx
  SubsurfaceMethod subsurface_method = SubsurfaceMethod::kRandomWalk;
};

}  // namespace fb
