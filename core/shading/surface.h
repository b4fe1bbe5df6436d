// How a surface scatters light at one hit: the closures its material made there, each with its
// weight, as Cycles' ShaderData holds them (intern/cycles/kernel/closure/, and svm_closure.h for
// how a shader node turns into closures). The host builds one per hit
// (core/texture/surface_shader.cpp) for the direction the ray arrived from; integrators reach it
// through fb_scene_api's bsdf_eval() and bsdf_sample() (core/render/trace_context.cpp).
//
// Evaluation sums the closures; sampling picks one closure in proportion to its sample weight,
// samples it, and evaluates all of them in the direction drawn (one-sample MIS over the closures,
// Cycles' _shader_bsdf_multi_eval), so that the estimate is unbiased whatever the sample weights.
#pragma once

#include <optional>

#include <filmback/geometry.h>
#include <filmback/vec.h>

#include "core/scene/shader_graph.h"
#include "core/shading/gltf_bsdf.h"

namespace fb {

// The hit as shading sees it, in render space, turned to the side the ray arrived from (Cycles
// flips N and Ng on back faces, shader_setup_from_ray).
struct ShadingFrame {
  Vec3f I;   // unit, from the hit back towards where the ray came from (Cycles' sd->I)
  Vec3f Ng;  // geometric normal, on I's side
  Vec3f N;   // interpolated shading normal before any normal map, on I's side (Cycles' sd->N)
  bool backfacing = false;  // the ray arrived at the back face (for a closed mesh: from inside)
};

// glTF metallic-roughness (gltf_bsdf.h) with its shading normal, normal map applied.
struct GltfSurfaceParams {
  Rgb base_color{1.f, 1.f, 1.f};
  float metallic = 0.f, roughness = 1.f, transmission = 0.f;
  float ior = 1.5f;  // of the material; the surface takes the ratio for the side it is seen from
  float specular = 1.f;
  Vec3f normal;  // unit, the mapped shading normal on the front side (fb_hit's orientation)
};

// A Principled BSDF's inputs (Blender 3.4's sockets) evaluated at the hit. Normals on the front
// side (fb_hit's orientation); the tangent unit or zero.
struct PrincipledInputs {
  Rgb base_color{0.8f, 0.8f, 0.8f};
  float subsurface = 0.f;
  Rgb subsurface_radius{1.f, 0.2f, 0.1f};
  Rgb subsurface_color{0.8f, 0.8f, 0.8f};
  float subsurface_ior = 1.4f, subsurface_anisotropy = 0.f;
  float metallic = 0.f, specular = 0.5f, specular_tint = 0.f, roughness = 0.5f;
  float anisotropic = 0.f, anisotropic_rotation = 0.f;
  float sheen = 0.f, sheen_tint = 0.5f;
  float clearcoat = 0.f, clearcoat_roughness = 0.03f;
  float ior = 1.45f, transmission = 0.f, transmission_roughness = 0.f;
  Vec3f normal, clearcoat_normal, tangent;
  Distribution distribution = Distribution::kGgx;
};

struct SurfaceSample {
  Vec3f wi;    // unit, away from the surface
  Rgb weight;  // f |cos| / pdf
  float pdf = 0.f;
  bool delta = false;         // a perfectly specular lobe: pdf is its choice probability
  bool transmission = false;  // wi leaves to the other side of the geometric surface
};

class Surface {
 public:
  void begin(const ShadingFrame& frame);
  void add_gltf(const GltfSurfaceParams& params);
  // Blender's shader nodes, each adding its closures times `weight` (the mix weights above it).
  void add_principled(const PrincipledInputs& inputs, Rgb weight);
  void add_diffuse(Rgb color, float roughness, Vec3f normal, Rgb weight);
  void add_glossy(Distribution distribution, Rgb color, float roughness, Vec3f normal, Rgb weight);
  void add_glass(Distribution distribution, Rgb color, float roughness, float ior, Vec3f normal,
                 Rgb weight);

  // f(I, wi) |N.wi| summed over the closures, and the solid-angle pdf sample() draws wi with: 0
  // where it never draws it (across the geometric surface from where the lobe meant it).
  Rgb eval(Vec3f wi, float& pdf) const;
  // u[0] picks the closure, (u[1], u[2]) the direction. False when the sample carries no light.
  bool sample(const float u[3], SurfaceSample& s) const;
  bool empty() const { return !gltf_; }
  const ShadingFrame& frame() const { return frame_; }

 private:
  // A direction counts when the lobe's normal and the geometric normal put it on the same side:
  // elsewhere the closures' maths and the surface disagree about where it goes.
  bool consistent(Vec3f wi_world, Vec3f wi_local) const {
    return (dot(frame_.Ng, wi_world) > 0.f) == (wi_local.z > 0.f);
  }
  ShadingFrame frame_;
  // The glTF model, in the frame of its (valid) shading normal.
  struct Gltf {
    Frame frame;
    Bsdf bsdf;
    Vec3f wo;  // I in that frame
  };
  std::optional<Gltf> gltf_;
};

}  // namespace fb
