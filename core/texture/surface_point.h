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
  // How far each set's (u, v) moves per raster pixel along x and along y (the ray's footprint,
  // core/texture/ray_footprint.h), or zero when the ray carries none: textures read their finest
  // level.
  std::array<Vec2f, VertexTextureData::kSets> duv_dx{}, duv_dy{};
};

// Where a texture is read: the position and its change per raster pixel along x and y.
struct TexturePosition {
  Vec2f st{}, dst_dx{}, dst_dy{};
};

// Where texture coordinate set `set` puts the point in a texture, through a 2x3 transform
// `m` (TextureRef::uv_transform): (s, t) = [a b c; d e f] (u, v, 1); its derivatives go through
// the linear part. A set the mesh lacks reads (0, 0), unfiltered.
inline TexturePosition texture_position(const SurfacePoint& point, uint32_t set,
                                        const std::array<float, 6>& m) {
  if (set >= point.uv_sets) return {{m[2], m[5]}, {}, {}};
  const auto linear = [&m](Vec2f d) {
    return Vec2f{m[0] * d.x + m[1] * d.y, m[3] * d.x + m[4] * d.y};
  };
  const Vec2f uv = point.uv[set];
  return {linear(uv) + Vec2f{m[2], m[5]}, linear(point.duv_dx[set]), linear(point.duv_dy[set])};
}

}  // namespace fb
