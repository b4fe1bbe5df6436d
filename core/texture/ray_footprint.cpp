#include "core/texture/ray_footprint.h"

#include <filmback/geometry.h>

#include <algorithm>
#include <cmath>

namespace fb {

namespace {

bool finite(Vec3f v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Where the ray from `origin` along `direction` meets the plane through `position` of normal
// `normal`, as an offset from `position`; false when it runs parallel to it.
bool offset_on_plane(Vec3f origin, Vec3f direction, Vec3f position, Vec3f normal, Vec3f& offset) {
  const float along = dot(normal, direction);
  if (along == 0.f) return false;
  const float t = dot(normal, position - origin) / along;
  offset = origin + direction * t - position;
  return finite(offset);
}

}  // namespace

float footprint_scale(uint32_t samples_per_pixel) {
  return std::max(0.125f, 1.f / std::sqrt(float(std::max(samples_per_pixel, 1u))));
}

bool position_differentials(const FootprintSource& source, Vec3f ray_origin, Vec3f ray_direction,
                            Vec3f position, Vec3f normal, Vec3f& dp_dx, Vec3f& dp_dy) {
  if (const RayDifferential* d = source.differential) {
    // pbrt-v4 SurfaceInteraction::ComputeDifferentials: the neighbouring rays met with the
    // tangent plane.
    if (offset_on_plane(ray_origin + d->dx_origin, ray_direction + d->dx_direction, position,
                        normal, dp_dx) &&
        offset_on_plane(ray_origin + d->dy_origin, ray_direction + d->dy_direction, position,
                        normal, dp_dy)) {
      dp_dx *= source.scale, dp_dy *= source.scale;
      return true;
    }
  }
  if (source.spread.empty()) return false;
  // pbrt-v4 CameraBase::Approximate_dp_dxy: a beam from the camera (the render-space origin) to
  // the hit, as wide as the narrowest pixel's at that distance, projected along the beam onto the
  // tangent plane. Isotropic, so any two directions across the beam will do.
  const float distance = length(position);
  if (!(distance > 0.f)) return false;
  const Vec3f w = position / distance;
  const float along = dot(normal, w);
  if (along == 0.f) return false;
  const float width =
      (source.spread.origin_m + source.spread.direction_rad * distance) * source.scale;
  const Frame across(w);
  const auto onto_plane = [&](Vec3f v) { return v - w * (dot(normal, v) / along); };
  dp_dx = onto_plane(across.s * width);
  dp_dy = onto_plane(across.t * width);
  return finite(dp_dx) && finite(dp_dy);
}

void set_texture_differentials(const Vec3f p[3], const uint32_t corner[3],
                               const VertexTextureData& data, Vec3f dp_dx, Vec3f dp_dy,
                               SurfacePoint& point) {
  // dp = a e1 + b e2 over the edges from corner 0, in the least-squares sense (dp lies in the
  // triangle's plane up to rounding): the normal equations of the 2x2 Gram matrix.
  const Vec3f e1 = p[1] - p[0], e2 = p[2] - p[0];
  const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  if (!(det > 0.0) || !std::isfinite(det)) return;
  const auto edge_weights = [&](Vec3f dp) {
    const double r1 = dot(e1, dp), r2 = dot(e2, dp);
    return Vec2f{float((g22 * r1 - g12 * r2) / det), float((g11 * r2 - g12 * r1) / det)};
  };
  const Vec2f wx = edge_weights(dp_dx), wy = edge_weights(dp_dy);
  if (!std::isfinite(wx.x + wx.y + wy.x + wy.y)) return;
  for (uint32_t set = 0; set < point.uv_sets; ++set) {
    const std::vector<Vec2f>& uv = data.texcoords[set];
    const Vec2f du1 = uv[corner[1]] - uv[corner[0]], du2 = uv[corner[2]] - uv[corner[0]];
    point.duv_dx[set] = du1 * wx.x + du2 * wx.y;
    point.duv_dy[set] = du1 * wy.x + du2 * wy.y;
  }
}

}  // namespace fb
