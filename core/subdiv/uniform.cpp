#include <opensubdiv/far/primvarRefiner.h>

#include <cmath>
#include <stdexcept>

#include "core/subdiv/refine.h"

namespace fb::subdiv {
namespace {

// The vertex type Far::PrimvarRefiner interpolates: a point or a tangent.
struct Point {
  float p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const Point& src, float weight) {
    for (int i = 0; i < 3; ++i)
      p[i] += weight * src.p[i];
  }
};

// Triangles the refinement will make: a quad gives four per level; an n-gon gives n quads at the
// first level.
uint64_t triangle_count(const fb_subdiv_cage& cage, uint32_t level) {
  uint64_t total = 0;
  for (uint32_t f = 0; f < cage.face_count; ++f) {
    const uint64_t n = cage.face_sizes[f];
    if (level == 0)
      total += n - 2;
    else
      total += 2 * (n == 4 ? 4 : n) << (2 * (level - 1));
  }
  return total;
}

}  // namespace

Triangles cage_limit(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage) {
  std::vector<Point> points(cage.vertex_count), limit(cage.vertex_count);
  for (uint32_t v = 0; v < cage.vertex_count; ++v)
    for (int i = 0; i < 3; ++i)
      points[v].p[i] = cage.positions[3 * v + i];
  Far::PrimvarRefiner(refiner).Limit(points.data(), limit);
  Triangles out;
  for (const Point& p : limit)
    out.positions.insert(out.positions.end(), {p.p[0], p.p[1], p.p[2]});
  return out;
}

Triangles refine_uniform(Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage, uint32_t level,
                         uint64_t max_triangles) {
  const uint64_t count = level > 24 ? UINT64_MAX : triangle_count(cage, level);
  if (count > max_triangles)
    throw std::runtime_error("level " + std::to_string(level) + " makes " + std::to_string(count) +
                             " triangles, more than the limit of " + std::to_string(max_triangles));
  // Full topology in the last level: the limit masks need each last-level vertex's neighbours.
  Far::TopologyRefiner::UniformOptions options{int(level)};
  options.fullTopologyInLastLevel = true;
  if (level > 0) refiner.RefineUniform(options);

  std::vector<Point> points(size_t(refiner.GetNumVerticesTotal()));
  for (uint32_t v = 0; v < cage.vertex_count; ++v)
    for (int i = 0; i < 3; ++i)
      points[v].p[i] = cage.positions[3 * v + i];
  const Far::PrimvarRefiner primvar(refiner);
  Point* src = points.data();
  for (int l = 1; l <= int(level); ++l) {
    Point* dst = src + refiner.GetLevel(l - 1).GetNumVertices();
    primvar.Interpolate(l, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& last = refiner.GetLevel(int(level));
  const size_t n = size_t(last.GetNumVertices());
  // The limit tangents, whose cross product is the smooth normal (Far's limit masks; the
  // positions stay those of the refined cage).
  std::vector<Point> limit(n), du(n), dv(n);
  primvar.Limit(src, limit, du, dv);

  Triangles out;
  out.positions.resize(3 * n);
  out.normals.resize(3 * n);
  for (size_t v = 0; v < n; ++v) {
    const Point& p = src[v];
    const float* a = du[v].p;
    const float* b = dv[v].p;
    float nrm[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0]};
    const float len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (int i = 0; i < 3; ++i) {
      out.positions[3 * v + i] = p.p[i];
      out.normals[3 * v + i] = len > 0 ? nrm[i] / len : 0;
    }
  }
  // Quads split along their first diagonal, as Blender's tessellation of a quad (0-1-2, 0-2-3);
  // level 0 leaves the cage's n-gons, split into fans.
  out.indices.reserve(3 * count);
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const auto face = last.GetFaceVertices(f);
    for (int k = 2; k < face.size(); ++k)
      out.indices.insert(out.indices.end(),
                         {uint32_t(face[0]), uint32_t(face[k - 1]), uint32_t(face[k])});
  }
  return out;
}

}  // namespace fb::subdiv
