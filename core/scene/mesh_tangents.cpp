#include "core/scene/mesh_tangents.h"

#include <cmath>

namespace fb {

std::vector<std::array<float, 4>> mesh_tangents(const TriangleMesh& mesh,
                                                const std::vector<Vec2f>& uv) {
  const size_t n = mesh.positions.size();
  std::vector<Vec3f> t_sum(n), b_sum(n), n_sum(n);
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
    const Vec3f e1 = mesh.positions[b] - mesh.positions[a];
    const Vec3f e2 = mesh.positions[c] - mesh.positions[a];
    const Vec2f d1 = uv[b] - uv[a], d2 = uv[c] - uv[a];
    const float det = d1.x * d2.y - d2.x * d1.y;
    const Vec3f face = cross(e1, e2);
    if (!(std::abs(det) > 0.f)) continue;
    const Vec3f t = (e1 * d2.y - e2 * d1.y) / det;
    const Vec3f bt = (e2 * d1.x - e1 * d2.x) / det;
    for (uint32_t v : {a, b, c})
      t_sum[v] += t, b_sum[v] += bt, n_sum[v] += face;
  }
  std::vector<std::array<float, 4>> out(n, {0.f, 0.f, 0.f, 1.f});
  for (size_t v = 0; v < n; ++v) {
    Vec3f normal = mesh.normals.empty() ? n_sum[v] : mesh.normals[v];
    if (!(length(normal) > 0.f)) continue;
    normal = normalize(normal);
    const Vec3f t = t_sum[v] - normal * dot(normal, t_sum[v]);
    if (!(length(t) > 0.f) || !is_finite(t)) continue;
    const Vec3f u = normalize(t);
    const float w = dot(cross(normal, u), b_sum[v]) > 0.f ? -1.f : 1.f;
    out[v] = {u.x, u.y, u.z, w};
  }
  return out;
}

}  // namespace fb
