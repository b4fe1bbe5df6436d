#include "core/tessellate/marching_tetrahedra.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fb {

namespace {

// The cube's corners are numbered by bits x, y, z; these six tetrahedra around the diagonal from
// corner 0 to corner 7 fill it, and neighbouring cubes cut their shared face alike (Kuhn's
// triangulation), so the pieces join without cracks.
constexpr std::array<std::array<int, 4>, 6> kCubeTetrahedra = {{
    {0, 1, 3, 7},
    {0, 3, 2, 7},
    {0, 2, 6, 7},
    {0, 6, 4, 7},
    {0, 4, 5, 7},
    {0, 5, 1, 7},
}};

// Bisections of a crossed grid edge: the vertex within 2^-24 of a cell of the boundary.
constexpr int kMarchedEdgeBisections = 24;

class TetrahedraMesher {
 public:
  TetrahedraMesher(const MarchedSet& set, const Bounds3d& box, uint32_t cells, bool closed,
                   TriangleMesh& mesh)
      : set_(set), mesh_(mesh) {
    const Vec3d size = box.hi - box.lo;
    const double longest = std::max({size.x, size.y, size.z});
    const uint32_t most = std::clamp(cells, 2u, kMarchedMaxCells);
    for (int a = 0; a < 3; ++a)
      n_[a] = std::clamp(uint32_t(std::ceil(most * size[a] / longest)), 1u, most);
    lo_ = box.lo;
    cell_ = {size.x / n_[0], size.y / n_[1], size.z / n_[2]};
    if (!closed) return;
    // Closed, the grid reaches half a cell past the box, so that a boundary on the box lies
    // between grid points and closes the mesh.
    lo_ = lo_ - cell_ * 0.5;
    for (uint32_t& n : n_)
      n += 1;
  }

  void run() {
    const size_t points = size_t(n_[0] + 1) * (n_[1] + 1) * (n_[2] + 1);
    inside_.resize(points);
    for (uint32_t k = 0; k <= n_[2]; ++k)
      for (uint32_t j = 0; j <= n_[1]; ++j)
        for (uint32_t i = 0; i <= n_[0]; ++i)
          inside_[index(i, j, k)] = set_.holds(point(i, j, k));
    for (uint32_t k = 0; k < n_[2]; ++k)
      for (uint32_t j = 0; j < n_[1]; ++j)
        for (uint32_t i = 0; i < n_[0]; ++i)
          cube(i, j, k);
  }

 private:
  size_t index(uint32_t i, uint32_t j, uint32_t k) const {
    return (size_t(k) * (n_[1] + 1) + j) * (n_[0] + 1) + i;
  }
  Vec3d point(uint32_t i, uint32_t j, uint32_t k) const {
    return lo_ + Vec3d{cell_.x * i, cell_.y * j, cell_.z * k};
  }
  void cube(uint32_t i, uint32_t j, uint32_t k) {
    size_t corner[8];
    for (int c = 0; c < 8; ++c)
      corner[c] = index(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
    for (const auto& tet : kCubeTetrahedra) {
      std::array<size_t, 4> in{}, out{};
      int ins = 0, outs = 0;
      for (int c : tet)
        (inside_[corner[c]] ? in[size_t(ins++)] : out[size_t(outs++)]) = corner[c];
      if (ins == 0 || outs == 0) continue;
      Vec3d inside_middle{0, 0, 0};
      for (int c = 0; c < ins; ++c)
        inside_middle = inside_middle + position(in[size_t(c)]);
      inside_middle = inside_middle / double(ins);
      if (ins == 1 || outs == 1) {  // one corner apart: the three edges from it
        const bool lone_inside = ins == 1;
        const size_t lone = lone_inside ? in[0] : out[0];
        const auto& others = lone_inside ? out : in;
        triangle(vertex(lone, others[0]), vertex(lone, others[1]), vertex(lone, others[2]),
                 inside_middle);
        continue;
      }
      // two and two: the quadrilateral of the four crossed edges, in order around it
      const uint32_t a = vertex(in[0], out[0]), b = vertex(in[0], out[1]),
                     c = vertex(in[1], out[1]), d = vertex(in[1], out[0]);
      triangle(a, b, c, inside_middle);
      triangle(a, c, d, inside_middle);
    }
  }

  Vec3d position(size_t grid_index) const {
    const size_t row = n_[0] + 1, layer = row * (n_[1] + 1);
    return point(uint32_t(grid_index % row), uint32_t(grid_index / row % (n_[1] + 1)),
                 uint32_t(grid_index / layer));
  }

  // The mesh vertex where the boundary crosses the edge between grid points a and b, one inside
  // and one outside, shared by every tetrahedron with that edge.
  uint32_t vertex(size_t a, size_t b) {
    if (!inside_[a]) std::swap(a, b);
    const uint64_t key = uint64_t(std::min(a, b)) << 32 | uint64_t(std::max(a, b));
    const auto [it, fresh] = vertices_.try_emplace(key, uint32_t(mesh_.positions.size()));
    if (!fresh) return it->second;
    Vec3d in = position(a), out = position(b);
    for (int i = 0; i < kMarchedEdgeBisections; ++i) {
      const Vec3d mid = (in + out) * 0.5;
      (set_.holds(mid) ? in : out) = mid;
    }
    const Vec3d p = (in + out) * 0.5;
    const Vec3d g = set_.normal(p, out);
    const double len = length(g);
    mesh_.positions.push_back(Vec3f(p));
    mesh_.normals.push_back(len > 0 && std::isfinite(len) ? Vec3f(g / len) : Vec3f{0, 0, 0});
    return it->second;
  }

  // Wound counter-clockwise seen from outside: its normal points away from the inside corners.
  void triangle(uint32_t a, uint32_t b, uint32_t c, Vec3d inside_middle) {
    const Vec3d pa = Vec3d(mesh_.positions[a]), pb = Vec3d(mesh_.positions[b]),
                pc = Vec3d(mesh_.positions[c]);
    const Vec3d n = cross(pb - pa, pc - pa);
    if (!(dot(n, n) > 0)) return;
    if (!set_.keeps((pa + pb + pc) / 3.0)) return;
    if (dot(n, (pa + pb + pc) / 3.0 - inside_middle) < 0) std::swap(b, c);
    mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
  }

  const MarchedSet& set_;
  TriangleMesh& mesh_;
  uint32_t n_[3] = {1, 1, 1};
  Vec3d lo_, cell_;
  std::vector<bool> inside_;
  std::unordered_map<uint64_t, uint32_t> vertices_;
};

}  // namespace

void march_tetrahedra(const MarchedSet& set, const Bounds3d& box, uint32_t cells, bool closed,
                      TriangleMesh& mesh) {
  TetrahedraMesher(set, box, cells, closed, mesh).run();
}

}  // namespace fb
