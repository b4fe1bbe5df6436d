// The host's half of materials: evaluates a material's textures at a surface point (through
// OpenImageIO's TextureSystem: tiled, cached, mip-mapped on demand) and writes the result into
// the hit record integrators read (fb_hit's surface fields, docs/plugins.md "Surfaces").
#pragma once

#include <memory>
#include <vector>

#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

#include "core/scene/scene.h"
#include "core/shading/surface.h"

namespace fb {

// Where on a surface a hit lies, interpolated from its vertices (render space).
struct SurfacePoint {
  // The hit's position in render space, for solid textures (Material::base_color_pattern), which
  // SurfaceShader evaluates in world space. Filled by render_geometry for meshes and analytic
  // solids alike.
  Vec3f position{};
  std::array<Vec2f, VertexTextureData::kSets> uv{};
  uint32_t uv_sets = 0;  // how many of `uv` the mesh has
  Vec3f tangent{};       // unit, or zero when the mesh has none
  float bitangent_sign = 1.f;
};

class SurfaceShader {
 public:
  // Opens every image a material uses; an image that cannot be read or is too large is an
  // InputError naming it. `world_from_render` places SurfacePoint::position in the world.
  explicit SurfaceShader(const Scene& scene, const Transform& world_from_render = Transform());
  ~SurfaceShader();
  SurfaceShader(const SurfaceShader&) = delete;
  SurfaceShader& operator=(const SurfaceShader&) = delete;

  // Fills hit.base_color ... hit.emission for `material` and applies its normal map to
  // hit.shading_normal (which must hold the interpolated normal).
  void shade(uint32_t material, const SurfacePoint& point, fb_hit& hit) const;
  // The same, and the closures for a ray arriving along `ray_direction` into `surface`
  // (hit.geometric_normal must be set too).
  void shade(uint32_t material, const SurfacePoint& point, Vec3f ray_direction, fb_hit& hit,
             Surface& surface) const;
  // Radiance leaving the point: the emissive factor (with its strength) times the texture.
  Rgb emission(uint32_t material, const SurfacePoint& point) const;
  // Coverage in [0, 1]: alpha factor times base colour texture alpha (glTF "Alpha Coverage"),
  // times 1 - transmit of a solid texture.
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
  const std::vector<Material>& materials_;
  Transform world_from_render_;
  struct Textures;
  std::unique_ptr<Textures> textures_;
};

// sRGB transfer function, decoding (IEC 61966-2-1).
float srgb_to_linear(float v);

}  // namespace fb
