// How a surface scatters light at one hit: the closures its material made there, each with its
// weight and sample weight, as Cycles 3.4's ShaderData holds them (kernel/closure/, and
// kernel/svm/closure.h for how a shader node turns into closures: node_closures.cpp). The host
// builds one per hit (core/texture/surface_shader.cpp) for the direction the ray arrived from;
// integrators reach it through fb_scene_api's bsdf_eval() and bsdf_sample()
// (core/render/trace_context.cpp).
//
// A surface holds either glTF's metallic-roughness model (add_gltf) or Blender closures (the
// node entry points), never both: each kind of material makes one kind.
//
// Evaluation sums the closures; sampling picks one closure in proportion to its sample weight,
// samples it, and evaluates all of them in the direction drawn (one-sample MIS over the closures,
// Cycles' surface_shader_bsdf_sample_closure and _surface_shader_bsdf_eval_mis), so that the
// estimate is unbiased whatever the sample weights. As in Cycles, a closure counts in a direction
// only where its own pdf is not zero. Unlike Cycles, the pdf reported for a direction leaves out
// the closures whose sampling never goes there (reflection closures refuse directions below the
// geometric normal): light sampling then takes the whole weight, where Cycles' MIS loses it.
#pragma once

#include <algorithm>
#include <optional>

#include <filmback/geometry.h>
#include <filmback/vec.h>

#include "core/shading/closure.h"
#include "core/shading/gltf_bsdf.h"
#include "core/shading/node_inputs.h"

namespace fb {

// The hit as shading sees it, in render space, turned to the side the ray arrived from (Cycles
// flips N and Ng on back faces, shader_setup_from_ray).
struct ShadingFrame {
  Vec3f I;   // unit, from the hit back towards where the ray came from (Cycles' sd->I)
  Vec3f Ng;  // geometric normal, on I's side
  Vec3f N;   // interpolated shading normal before any normal map, on I's side (Cycles' sd->N)
  bool backfacing = false;  // the ray arrived at the back face (for a closed mesh: from inside)
  // The ray came from the camera (Cycles: bounce and transparent bounce 0). Cycles then samples
  // every closure with at least 1/8 of the summed sample weight ("defensive sampling",
  // surface_shader_prepare_closures). Only the variance depends on it, except for the
  // clearcoat, whose pdf is not its sampling density: its albedo then depends on how often it
  // is picked (2-3 % at clearcoat 1 over a rough dielectric, docs/blender.md).
  bool camera_ray = false;
};

// glTF metallic-roughness (gltf_bsdf.h) with its shading normal, normal map applied.
struct GltfSurfaceParams {
  Rgb base_color{1.f, 1.f, 1.f};
  float metallic = 0.f, roughness = 1.f, transmission = 0.f;
  float ior = 1.5f;  // of the material; the surface takes the ratio for the side it is seen from
  float specular = 1.f;
  Vec3f normal;  // unit, the mapped shading normal on the front side (fb_hit's orientation)
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
  // At most this many closures (Cycles allows 64, MAX_CLOSURE, counting the extra storage its
  // microfacets take). One Principled BSDF makes at most six; beyond the capacity the closure
  // with the lowest sample weight is dropped, the earliest of equals kept.
  static constexpr int kMaxClosures = 16;

  void begin(const ShadingFrame& frame);
  void add_gltf(const GltfSurfaceParams& params);

  // Blender 3.4's closure nodes, each with the weight the node gets from the Mix and Add Shader
  // nodes above it (node_closures.cpp, after Cycles' svm_node_closure_bsdf).
  void add_principled(const PrincipledInputs& in, Rgb weight);
  // Lambert for roughness 0, else Oren-Nayar.
  void add_diffuse(Rgb color, float roughness, Vec3f normal, Rgb weight);
  void add_glossy(Distribution distribution, Rgb color, float roughness, Vec3f normal, Rgb weight);
  void add_glass(Distribution distribution, Rgb color, float roughness, float ior, Vec3f normal,
                 Rgb weight);

  // f(I, wi) |N.wi| summed over the closures, and the solid-angle pdf sample() draws wi with: 0
  // where it never draws it (across the geometric surface from where the lobe meant it).
  Rgb eval(Vec3f wi, float& pdf) const;
  // u[0] picks the closure, (u[1], u[2]) the direction. False when the sample carries no light.
  bool sample(const float u[3], SurfaceSample& s) const;
  // The summed weights of the closures of one kind (glTF's model: of its lobes), Cycles'
  // surface_shader_diffuse, _glossy and _transmission: what the DiffCol, GlossCol and TransCol
  // passes hold at a camera ray's first hit.
  Rgb closure_weight(ClosureKind kind) const;
  bool empty() const { return !gltf_ && count_ == 0; }
  const ShadingFrame& frame() const { return frame_; }
  int closure_count() const { return count_; }
  const Closure& closure(int i) const { return closures_[i]; }

 private:
  // Cycles' bsdf_alloc: negative weights become zero, the sample weight is the weight's
  // average, and a closure below kClosureWeightCutoff is not made (null).
  Closure* allocate(ClosureType type, Rgb weight, Vec3f N);
  // A node's Normal input turned to I's side (zero: the interpolated normal), then
  // ensure_valid_reflection as svm_node_closure_bsdf applies it.
  Vec3f node_normal(Vec3f normal) const;
  // The Principled BSDF's lobes, each made from what add_principled computes once for all of them
  // (node_closures.cpp).
  struct PrincipledCommon;
  void add_principled_diffuse(const PrincipledCommon& p);
  void add_principled_sheen(const PrincipledCommon& p);
  void add_principled_specular(const PrincipledCommon& p);
  void add_principled_transmission(const PrincipledCommon& p);
  void add_principled_clearcoat(const PrincipledCommon& p);
  ClosureContext context() const { return {frame_.I, frame_.Ng, frame_.N}; }
  // Cycles' bump shadowing of a diffuse closure whose normal differs from the interpolated one.
  float bump_factor(const Closure& c, Vec3f wi) const;
  // Whether closure c's sampling can return wi: reflection closures refuse directions below the
  // geometric normal.
  bool reachable(const Closure& c, Vec3f wi) const;
  // How sample() picks closures: by sample weight, raised to `floor` (defensive sampling).
  struct Picking {
    float floor, sum;
    float weight(const Closure& c) const { return std::max(c.sample_weight, floor); }
  };
  Picking picking() const;
  // The sums over the closures other than `skip` of f |cos| and pdf x picking weight.
  Rgb accumulate(Vec3f wi, const Closure* skip, const Picking& picking, float& weighted_pdf) const;

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
  int count_ = 0;
  Closure closures_[kMaxClosures];
};

}  // namespace fb
