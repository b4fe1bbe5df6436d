// Where on a surface a hit lies: what textures are looked up with.
#pragma once

#include <array>
#include <cstdint>

#include <filmback/vec.h>

#include "core/scene/material_textures.h"

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
  Vec3f radial_tangent{};  // VertexTextureData::radial_tangents in render space, or zero
};

// Where texture coordinate set `set` puts the point in a texture, through a 2x3 transform
// `m` (TextureRef::uv_transform): (s, t) = [a b c; d e f] (u, v, 1). A set the mesh lacks reads
// (0, 0).
inline Vec2f texture_position(const SurfacePoint& point, uint32_t set,
                              const std::array<float, 6>& m) {
  const Vec2f uv = set < point.uv_sets ? point.uv[set] : Vec2f{0.f, 0.f};
  return {m[0] * uv.x + m[1] * uv.y + m[2], m[3] * uv.x + m[4] * uv.y + m[5]};
}

}  // namespace fb
