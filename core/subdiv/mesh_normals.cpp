#include <cmath>

#include "core/subdiv/refine.h"

namespace fb::subdiv {
namespace {

struct Vec {
  double x = 0, y = 0, z = 0;
};
Vec operator-(const Vec& a, const Vec& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
double dot(const Vec& a, const Vec& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec unit(const Vec& a) {
  const double length = std::sqrt(dot(a, a));
  return length > 0 ? Vec{a.x / length, a.y / length, a.z / length} : Vec{};
}

}  // namespace

void mesh_normals(const std::vector<float>& positions, const std::vector<uint32_t>& polygons,
                  const std::vector<uint32_t>& owner, std::vector<float>& normals) {
  const auto point = [&](uint32_t v) {
    return Vec{positions[3 * size_t(v)], positions[3 * size_t(v) + 1],
               positions[3 * size_t(v) + 2]};
  };
  std::vector<Vec> sums(owner.size());
  for (size_t at = 0; at < polygons.size(); at += 1 + polygons[at]) {
    const uint32_t n = polygons[at];
    const uint32_t* vertices = &polygons[at + 1];
    // Newell's normal: the polygon's vector area (for a quad, half the cross product of its
    // diagonals, as Blender's normal_quad_v3).
    Vec area;
    for (uint32_t k = 0; k < n; ++k) {
      const Vec a = point(vertices[k]), b = point(vertices[(k + 1) % n]);
      area.x += (a.y - b.y) * (a.z + b.z);
      area.y += (a.z - b.z) * (a.x + b.x);
      area.z += (a.x - b.x) * (a.y + b.y);
    }
    const Vec normal = unit(area);
    for (uint32_t k = 0; k < n; ++k) {
      const Vec here = point(vertices[k]);
      const Vec to_previous = unit(point(vertices[(k + n - 1) % n]) - here);
      const Vec to_next = unit(point(vertices[(k + 1) % n]) - here);
      const double angle = std::acos(std::fmax(-1.0, std::fmin(1.0, dot(to_previous, to_next))));
      Vec& sum = sums[owner[vertices[k]]];
      sum.x += angle * normal.x, sum.y += angle * normal.y, sum.z += angle * normal.z;
    }
  }
  for (size_t v = 0; v < owner.size(); ++v) {
    const Vec n = unit(sums[owner[v]]);
    if (dot(n, n) == 0) continue;
    normals[3 * v] = float(n.x), normals[3 * v + 1] = float(n.y), normals[3 * v + 2] = float(n.z);
  }
}

}  // namespace fb::subdiv
