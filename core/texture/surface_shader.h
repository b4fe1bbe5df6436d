// The host's half of materials: evaluates a material at a surface point, its textures through
// OpenImageIO (core/texture/texture_images.h), into the hit record integrators read (fb_hit's
// surface fields) and the hit's Surface, the closures they scatter with (docs/plugins.md
// "Surfaces"). glTF's metallic-roughness materials make one closure (core/shading/gltf_bsdf.h);
// Blender's shader graphs the closures Cycles makes of them (core/texture/graph_shader.h).
#pragma once

#include <optional>
#include <vector>

#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

#include "core/scene/scene.h"
#include "core/shading/surface.h"
#include "core/texture/graph_shader.h"
#include "core/texture/surface_point.h"
#include "core/texture/texture_images.h"

namespace fb {

class SurfaceShader {
 public:
  // Opens every image a material uses; an image that cannot be read or is too large is an
  // InputError naming it. `world_from_render` places SurfacePoint::position in the world.
  explicit SurfaceShader(const Scene& scene, const Transform& world_from_render = Transform());
  SurfaceShader(const SurfaceShader&) = delete;
  SurfaceShader& operator=(const SurfaceShader&) = delete;

  // Fills hit.base_color ... hit.emission for `material` and applies its normal map to
  // hit.shading_normal (which must hold the interpolated normal).
  void shade(uint32_t material, const SurfacePoint& point, fb_hit& hit) const;
  // The same, and the closures for a ray arriving along `ray_direction` (from the camera when
  // `camera_ray`) into `surface` (hit.geometric_normal must be set too).
  void shade(uint32_t material, const SurfacePoint& point, Vec3f ray_direction, bool camera_ray,
             fb_hit& hit, Surface& surface) const;
  // Radiance leaving the point: the emissive factor (with its strength) times the texture (or a
  // POV-Ray pigment, and its texture layers' composited as shade() composites their colours), or
  // the shader graph's emission.
  Rgb emission(uint32_t material, const SurfacePoint& point) const;
  // Coverage in [0, 1]: alpha factor times base colour texture alpha (glTF "Alpha Coverage"),
  // times 1 - transmit of a solid texture; a shader graph's 1 - transparency.
  float alpha(uint32_t material, const SurfacePoint& point) const;
  bool has_alpha(uint32_t material) const {
    return materials_[material].alpha_mode != AlphaMode::kOpaque;
  }
  // Whether a hit at `point` counts (glTF "Alpha Coverage"): MASK keeps it when alpha reaches the
  // cutoff, BLEND with probability alpha (stochastic transparency, Enderton et al. 2010), decided
  // by `hit_hash`, a hash of the ray and the hit, so that a render stays deterministic. Meshes
  // ask it in Embree's filter, analytic solids for each surface they cross.
  bool covers(uint32_t material, const SurfacePoint& point, uint64_t hit_hash) const;

 private:
  // RGBA of texture `ref` at the point; `srgb` decodes the colour channels.
  std::array<float, 4> lookup(const TextureRef& ref, const SurfacePoint& point, bool srgb) const;
  SolidColour solid_colour(const SolidPattern& pattern, const SurfacePoint& point) const;
  // How a POV-Ray texture layer at the point covers what is below it.
  struct LayerCover {
    Rgb colour;   // its pigment's
    float cover;  // 1 - filter - transmit: the share of the layer's own colour
    Rgb through;  // filter times its colour, plus transmit: what passes from below
  };
  LayerCover layer_cover(const Material& layer, const SurfacePoint& point) const;
  const std::vector<Material>& materials_;
  Transform world_from_render_;
  TextureImages images_;
  std::vector<std::optional<GraphShader>> graphs_;  // per material: its shader graph's
};

}  // namespace fb
