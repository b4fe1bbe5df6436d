#include "core/tessellate/seam_join.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "core/math/mesh_geometry.h"

namespace fb {

namespace {

constexpr uint64_t kNoSeam = UINT64_MAX;
// Cut vertices of the two sides closer than this fraction of the tolerance are made one (both
// sides computed the same point of the curve, e.g. where it meets a sharp edge).
constexpr double kSnapFraction = 1e-3;
// Both sides' vertices lie on the crossing curve and each side's chords within the tolerance of
// it, so a vertex of one side lies within the tolerance of the other side's chord; the margin
// covers the bisection's own error.
constexpr double kReachFraction = 1.5;

// The seam between two primitives, the same seen from either.
uint64_t seam_of(uint32_t leaf, uint32_t partner) {
  if (partner == TrimmedSurface::kNoPartner) return kNoSeam;
  return (uint64_t(std::min(leaf, partner)) << 32) | std::max(leaf, partner);
}

uint64_t directed(uint32_t a, uint32_t b) {
  return (uint64_t(a) << 32) | b;
}

// Vertices hashed by the cube of side `cell` they fall in.
class Grid {
 public:
  explicit Grid(double cell) : cell_(cell) {}
  void add(Vec3d p, uint32_t v) { cells_[key(cell_of(p))].push_back(v); }
  // Every vertex in the cells that the box around [a, b] widened by `margin` overlaps.
  template <typename Visit>
  void near(Vec3d a, Vec3d b, double margin, Visit&& visit) const {
    const Vec3d m{margin, margin, margin};
    const std::array<int64_t, 3> lo = cell_of(min(a, b) - m), hi = cell_of(max(a, b) + m);
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z)
          if (const auto it = cells_.find(key({x, y, z})); it != cells_.end())
            for (uint32_t v : it->second)
              visit(v);
  }

 private:
  std::array<int64_t, 3> cell_of(Vec3d p) const {
    return {int64_t(std::floor(p.x / cell_)), int64_t(std::floor(p.y / cell_)),
            int64_t(std::floor(p.z / cell_))};
  }
  static uint64_t key(const std::array<int64_t, 3>& c) {
    return uint64_t(c[0]) * 73856093u ^ uint64_t(c[1]) * 19349663u ^ uint64_t(c[2]) * 83492791u;
  }
  double cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

struct Insertion {
  double t;  // along the edge
  uint32_t vertex;
};

// Where three primitives meet, each pair's seam ends at a point that no side has as a vertex,
// and a hole smaller than the tolerance is left between the three. Open loops of edges this short
// (in tolerances) are closed by a fan from their centroid, each triangle taking the material and
// normals of the triangle across its edge.
constexpr double kSmallHole = 4;

void fill_small_holes(JoinedSurface& s, double tolerance_m) {
  std::unordered_map<uint64_t, size_t> owner;  // directed edge -> a triangle with it
  for (size_t i = 0; i < s.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      owner.try_emplace(
          directed(s.triangles[i].v[size_t(k)], s.triangles[i].v[size_t((k + 1) % 3)]), i);
  std::unordered_map<uint32_t, std::vector<uint32_t>> open;  // u -> v for each open edge u -> v
  for (const auto& [edge, i] : owner) {
    const uint32_t a = uint32_t(edge >> 32), b = uint32_t(edge);
    if (!owner.count(directed(b, a))) open[a].push_back(b);
  }
  std::unordered_set<uint64_t> walked;
  const double longest = kSmallHole * tolerance_m;
  for (const auto& [start, ends] : open)
    for (uint32_t first : ends) {
      std::vector<uint32_t> loop{start};
      double perimeter = 0;
      uint32_t at = start, to = first;
      while (walked.insert(directed(at, to)).second) {
        perimeter += length(s.positions[to] - s.positions[at]);
        if (to == start || perimeter > longest) break;
        loop.push_back(to);
        const auto next = open.find(to);
        if (next == open.end()) break;
        at = to, to = next->second.front();
        for (uint32_t v : next->second)  // a vertex two open loops pass through: not walked yet
          if (!walked.count(directed(at, v))) to = v;
      }
      if (to != start || perimeter > longest || loop.size() < 3) continue;
      Vec3d centroid{0, 0, 0};
      for (uint32_t v : loop)
        centroid += s.positions[v];
      const uint32_t centre = uint32_t(s.positions.size());
      s.positions.push_back(centroid * (1.0 / double(loop.size())));
      for (size_t j = 0; j < loop.size(); ++j) {
        const uint32_t a = loop[j], b = loop[(j + 1) % loop.size()];
        const JoinedSurface::Triangle across = s.triangles[owner.at(directed(a, b))];
        Vec3d na = across.n[0], nb = across.n[0];
        for (size_t k = 0; k < 3; ++k) {
          if (across.v[k] == a) na = across.n[k];
          if (across.v[k] == b) nb = across.n[k];
        }
        s.triangles.push_back({{b, a, centre}, {nb, na, unit_or(na + nb, na)}, across.material});
      }
    }
}

// The parts' vertices and triangles in one list each, with where each came from.
struct Gathered {
  JoinedSurface surface;
  std::vector<uint32_t> leaf_of;  // per vertex: its primitive
  std::vector<uint64_t> seam;     // per vertex: the seam it was cut on, or kNoSeam
  std::vector<uint32_t> owner;    // per triangle: its primitive
};

Gathered gather(const std::vector<SurfacePart>& parts) {
  Gathered g;
  JoinedSurface& out = g.surface;
  for (const SurfacePart& part : parts) {
    const uint32_t base = uint32_t(out.positions.size());
    const TrimmedSurface& s = part.surface;
    out.positions.insert(out.positions.end(), s.positions.begin(), s.positions.end());
    for (uint32_t partner : s.partner) {
      g.leaf_of.push_back(part.leaf);
      g.seam.push_back(seam_of(part.leaf, partner));
    }
    for (const TrimmedSurface::Triangle& t : s.triangles) {
      out.triangles.push_back({{t.v[0] + base, t.v[1] + base, t.v[2] + base}, t.n, part.material});
      g.owner.push_back(part.leaf);
    }
  }
  return g;
}

// One vertex where both sides of a seam found the same point (within kSnapFraction of the
// tolerance); the triangles this collapses are dropped.
void merge_shared_cut_vertices(Gathered& g, double tolerance_m) {
  JoinedSurface& out = g.surface;
  std::vector<char> used(out.positions.size(), 0);
  for (const JoinedSurface::Triangle& t : out.triangles)
    for (uint32_t v : t.v)
      used[v] = 1;
  std::vector<uint32_t> same(out.positions.size());
  const double snap = kSnapFraction * tolerance_m;
  Grid grid(tolerance_m);
  for (uint32_t v = 0; v < out.positions.size(); ++v) {
    same[v] = v;
    if (!used[v] || g.seam[v] == kNoSeam) continue;
    grid.near(out.positions[v], out.positions[v], snap, [&](uint32_t w) {
      if (same[v] == v && g.seam[w] == g.seam[v] && g.leaf_of[w] != g.leaf_of[v] &&
          length(out.positions[w] - out.positions[v]) <= snap)
        same[v] = w;
    });
    if (same[v] == v) grid.add(out.positions[v], v);
  }
  std::vector<JoinedSurface::Triangle> kept;
  std::vector<uint32_t> kept_owner;
  for (size_t i = 0; i < out.triangles.size(); ++i) {
    JoinedSurface::Triangle t = out.triangles[i];
    for (uint32_t& v : t.v)
      v = same[v];
    if (t.v[0] == t.v[1] || t.v[1] == t.v[2] || t.v[2] == t.v[0]) continue;
    kept.push_back(t);
    kept_owner.push_back(g.owner[i]);
  }
  out.triangles.swap(kept);
  g.owner.swap(kept_owner);
}

// One seam's edges with nothing on their other side, and their vertices.
struct OpenSeam {
  std::vector<std::pair<size_t, int>> edges;  // triangle, edge
  std::vector<uint32_t> vertices;
  double longest = 0;
};

std::unordered_map<uint64_t, OpenSeam> open_seams(const Gathered& g) {
  const JoinedSurface& out = g.surface;
  std::unordered_set<uint64_t> edges;
  for (const JoinedSurface::Triangle& t : out.triangles)
    for (int k = 0; k < 3; ++k)
      edges.insert(directed(t.v[size_t(k)], t.v[size_t((k + 1) % 3)]));
  std::unordered_map<uint64_t, OpenSeam> seams;
  std::vector<char> listed(out.positions.size(), 0);
  for (size_t i = 0; i < out.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = out.triangles[i].v[size_t(k)], b = out.triangles[i].v[size_t((k + 1) % 3)];
      if (g.seam[a] == kNoSeam || g.seam[a] != g.seam[b] || edges.count(directed(b, a))) continue;
      OpenSeam& s = seams[g.seam[a]];
      s.edges.push_back({i, k});
      s.longest = std::max(s.longest, length(out.positions[b] - out.positions[a]));
      for (uint32_t v : {a, b})
        if (!listed[v]) listed[v] = 1, s.vertices.push_back(v);
    }
  return seams;
}

// Vertices to insert into triangle edges, keyed by triangle * 3 + edge, in order along the edge.
using Insertions = std::unordered_map<uint64_t, std::vector<Insertion>>;

// Each vertex of one side of `s` goes into the nearest open edge of the other side (where the seam
// turns at a sharp edge, the nearest is on the vertex's own branch).
void add_seam_insertions(const Gathered& g, const OpenSeam& s, double tolerance_m,
                         Insertions& insertions) {
  const JoinedSurface& out = g.surface;
  const double snap = kSnapFraction * tolerance_m;
  const double reach = kReachFraction * tolerance_m;
  Grid near(std::max(s.longest, tolerance_m));
  for (uint32_t v : s.vertices)
    near.add(out.positions[v], v);
  struct Best {
    double distance, overshoot;  // to the segment; beyond its ends along it
    uint64_t edge;
    double t;
  };
  std::unordered_map<uint32_t, Best> best;
  for (const std::pair<size_t, int>& edge : s.edges) {
    // Named copies, not a structured binding: clang 14 cannot capture one in the lambda below.
    const size_t i = edge.first;
    const int k = edge.second;
    const uint32_t a = out.triangles[i].v[size_t(k)], b = out.triangles[i].v[size_t((k + 1) % 3)];
    const Vec3d pa = out.positions[a], pb = out.positions[b], ab = pb - pa;
    near.near(pa, pb, reach, [&](uint32_t w) {
      if (w == a || w == b || g.leaf_of[w] == g.owner[i]) return;
      const Vec3d p = out.positions[w];
      if (length(p - pa) <= snap || length(p - pb) <= snap) return;
      const double t = dot(p - pa, ab) / dot(ab, ab);
      const double distance = distance_to_segment(p, pa, pb);
      const double overshoot = std::max({0.0, -t, t - 1}) * length(ab);
      if (distance > reach) return;
      const Best candidate{distance, overshoot, uint64_t(i) * 3 + uint64_t(k), t};
      const auto [it, added] = best.try_emplace(w, candidate);
      // Past the shared end of two edges it is equally near both: the one it overshoots less.
      if (!added && (distance < it->second.distance - snap ||
                     (distance <= it->second.distance + snap && overshoot < it->second.overshoot)))
        it->second = candidate;
    });
  }
  for (const auto& [w, b] : best)
    insertions[b.edge].push_back({b.t, w});
}

Insertions seam_insertions(const Gathered& g, double tolerance_m) {
  Insertions insertions;
  for (const auto& [key, s] : open_seams(g))
    add_seam_insertions(g, s, tolerance_m, insertions);
  for (auto& [edge, along] : insertions)
    std::sort(along.begin(), along.end(),
              [](const Insertion& x, const Insertion& y) { return x.t < y.t; });
  return insertions;
}

// Triangle `i` with the new vertices on its edges, as a fan: from the opposite corner when they
// are on one edge, else from its centroid (a new vertex).
void refan_triangle(JoinedSurface& out, size_t i, const Insertions& insertions,
                    std::vector<JoinedSurface::Triangle>& rebuilt) {
  const JoinedSurface::Triangle& t = out.triangles[i];
  std::vector<uint32_t> ring;
  std::vector<Vec3d> normals;
  int edges_with = 0, last = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t a = size_t(k), b = size_t((k + 1) % 3);
    ring.push_back(t.v[a]);
    normals.push_back(t.n[a]);
    const auto it = insertions.find(uint64_t(i) * 3 + uint64_t(k));
    if (it == insertions.end()) continue;
    ++edges_with, last = k;
    for (const Insertion& in : it->second) {
      ring.push_back(in.vertex);
      normals.push_back(unit_or(t.n[a] * (1 - in.t) + t.n[b] * in.t, t.n[a]));
    }
  }
  if (edges_with == 0) {
    rebuilt.push_back(t);
    return;
  }
  const size_t n = ring.size();
  if (edges_with == 1) {
    // The ring starts at corner 0; the corner opposite edge `last` is corner last + 2.
    size_t apex = 0;
    for (size_t j = 0; j < n; ++j)
      if (ring[j] == t.v[size_t((last + 2) % 3)]) apex = j;
    for (size_t j = 1; j + 1 < n; ++j) {
      const size_t u = (apex + j) % n, w = (apex + j + 1) % n;
      rebuilt.push_back(
          {{ring[apex], ring[u], ring[w]}, {normals[apex], normals[u], normals[w]}, t.material});
    }
    return;
  }
  const uint32_t centre = uint32_t(out.positions.size());
  out.positions.push_back((out.positions[t.v[0]] + out.positions[t.v[1]] + out.positions[t.v[2]]) *
                          (1.0 / 3));
  const Vec3d nc = unit_or(t.n[0] + t.n[1] + t.n[2], t.n[0]);
  for (size_t j = 0; j < n; ++j)
    rebuilt.push_back(
        {{centre, ring[j], ring[(j + 1) % n]}, {nc, normals[j], normals[(j + 1) % n]}, t.material});
}

}  // namespace

// The steps of the header's join: gather the parts, make each point both sides of a seam found
// into one vertex, insert each side's remaining cut vertices into the other side's open seam
// edges, re-triangulate the triangles that received some, and close the small holes left where
// three primitives meet.
JoinedSurface join_surfaces(const std::vector<SurfacePart>& parts, double tolerance_m) {
  Gathered g = gather(parts);
  merge_shared_cut_vertices(g, tolerance_m);
  const Insertions insertions = seam_insertions(g, tolerance_m);
  JoinedSurface& out = g.surface;
  std::vector<JoinedSurface::Triangle> rebuilt;
  for (size_t i = 0; i < out.triangles.size(); ++i)
    refan_triangle(out, i, insertions, rebuilt);
  out.triangles.swap(rebuilt);
  fill_small_holes(out, tolerance_m);
  return std::move(g.surface);
}

}  // namespace fb
