#include "core/tessellate/csg_trim.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <unordered_map>
#include <utility>

#include "core/math/mesh_geometry.h"

namespace fb {

namespace {

constexpr int kUnknown = 2;  // a label not computed yet
constexpr int kMaxLevels =
    64;  // refinement levels: 2^-64 of a 10 km plane is far below any tolerance
// Bisection stops when the bracket is this fraction of the tolerance.
constexpr double kBisectionPrecision = 1e-7;
// A crossing this close to a vertex (a fraction of the tolerance) is at the vertex. Where two
// surfaces touch, their gap grows as the square of the distance from the contact, so within about
// 1e-8 of their size double precision cannot tell which side a point is on.
constexpr double kAtVertex = 1e-4;
// Labels look at the set this far (a fraction of the tolerance) on either side of the surface.
constexpr double kLabelOffset = 1e-4;
// A new vertex takes the exact surface's normal unless it is this far from its corners' mean
// (cos 45 degrees): then it lies on a sharp edge and keeps its face's normal.
constexpr double kCreaseCosine = 0.7071;

uint64_t edge_key(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
}

// Of three labels of which exactly two are equal, the other one's index.
int lone_corner(const int l[3]) {
  return l[1] == l[2] ? 0 : l[0] == l[2] ? 1 : 2;
}

struct Tri {
  std::array<uint32_t, 3> v;
  std::array<Vec3d, 3> n;
};

// Three vertex indices, or the bits of a float position.
struct TripleHash {
  size_t operator()(const std::array<uint32_t, 3>& k) const {
    return std::hash<uint64_t>()((uint64_t(k[0]) << 42) ^ (uint64_t(k[1]) << 21) ^ k[2]);
  }
};

class Trimmer {
 public:
  Trimmer(const CsgProbe& probe, size_t leaf, const TriangleBvh& boundaries,
          const TrimTolerances& tolerances)
      : probe_(probe),
        leaf_(leaf),
        boundaries_(boundaries),
        tolerance_(tolerances.cut_m),
        lift_reach_(2 * tolerances.mesh_m + tolerances.cut_m),
        beside_(2 * tolerances.boundaries_m + tolerances.cut_m) {}

  void load(const TriangleMesh& mesh);
  void refine();
  TrimmedSurface cut();

 private:
  struct Crossing {
    uint32_t vertex;
    double s;  // along the edge from its first vertex (as asked)
  };

  uint32_t add_vertex(Vec3d position, Vec3d surface_normal, uint32_t partner) {
    positions_.push_back(position);
    normals_.push_back(surface_normal);
    labels_.push_back(kUnknown);
    partners_.push_back(partner);
    return uint32_t(positions_.size() - 1);
  }
  int label(uint32_t v) {
    if (labels_[v] == kUnknown) labels_[v] = int8_t(label_at({positions_[v], normals_[v]}));
    return labels_[v];
  }
  int label_at(const CsgProbe::SurfacePoint& p) const {
    return probe_.label(p.position, p.normal, leaf_, kLabelOffset * tolerance_);
  }
  // The exact surface at a point of a triangle, lifted along the interpolated normal; the point
  // itself with that normal where the line misses the surface.
  CsgProbe::SurfacePoint surface_at(Vec3d flat, Vec3d normal) const {
    if (auto p = probe_.lift(leaf_, flat, normal, lift_reach_)) return *p;
    return {flat, normal};
  }
  // The normal a triangle gives its corner at new vertex v, s of the way from a corner with
  // normal na to one with nb.
  Vec3d corner_normal(uint32_t v, Vec3d na, Vec3d nb, double s) const {
    const Vec3d mean = unit_or(na * (1 - s) + nb * s, na);
    const Vec3d exact = normals_[v];
    return dot(exact, mean) >= kCreaseCosine ? exact : mean;
  }
  uint32_t midpoint(uint32_t a, uint32_t b, Vec3d na, Vec3d nb);
  Crossing crossing(uint32_t a, uint32_t b, Vec3d na, Vec3d nb);
  // Bisection for where the label changes from `from` along the lifted segment A -> B.
  struct Found {
    CsgProbe::SurfacePoint point;
    double s;
    uint32_t partner;
  };
  Found bisect(Vec3d a, Vec3d b, Vec3d na, Vec3d nb, int from);
  int longest_edge(const Tri& t) const;
  bool is_split(uint32_t a, uint32_t b) const { return midpoints_.count(edge_key(a, b)) > 0; }
  void subdivide(const Tri& t, std::vector<Tri>& out);
  bool cuts(const std::array<Vec3d, 2>& segment, Vec3d face, double size);
  bool needs_refinement(const Tri& t);
  double cut_error(const Tri& t, int lone);
  void emit(uint32_t a, uint32_t b, uint32_t c, Vec3d na, Vec3d nb, Vec3d nc, int label,
            TrimmedSurface& out) const;

  const CsgProbe& probe_;
  const size_t leaf_;
  const TriangleBvh& boundaries_;
  const double tolerance_;
  // Every point of the mesh lies within the primitive's own tolerance of its surface, so the
  // surface is sought no farther away: a longer search could find the far side of a thin box.
  const double lift_reach_;
  // Another primitive's tessellation strays from its surface by up to its own tolerance: labels
  // this far on either side of it are on either side of the surface itself.
  const double beside_;
  std::vector<Vec3d> positions_, normals_;
  std::vector<int8_t> labels_;
  std::vector<uint32_t> partners_;
  std::unordered_map<uint64_t, uint32_t> midpoints_;
  std::unordered_map<uint64_t, Crossing> crossings_;  // s from the edge's smaller vertex index
  std::unordered_map<std::array<uint32_t, 3>, bool, TripleHash> verdicts_;
  std::vector<Tri> mesh_;  // conforming: every split edge is split in both its triangles
  std::vector<const TaggedTriangle*> candidates_;
};

void Trimmer::load(const TriangleMesh& mesh) {
  const Transform& world_from_object = probe_.leaf(leaf_).world_from_object;
  const Transform normal_from_object = world_from_object.normal_transform();
  const bool mirrored = world_from_object.determinant3x3() < 0;
  // Welded: the tessellation repeats positions along its seams and sharp edges, which must be one
  // vertex for edges to be shared.
  std::unordered_map<std::array<uint32_t, 3>, uint32_t, TripleHash> welded;
  std::vector<uint32_t> vertex(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    // + 0: -0 and 0 are one position.
    const Vec3f p = mesh.positions[i] + Vec3f{0.f, 0.f, 0.f};
    std::array<uint32_t, 3> bits;
    std::memcpy(bits.data(), &p, sizeof bits);
    const auto [it, added] = welded.try_emplace(bits, uint32_t(positions_.size()));
    if (added)
      add_vertex(world_from_object.point(Vec3d(mesh.positions[i])), {0, 0, 0},
                 TrimmedSurface::kNoPartner);
    vertex[i] = it->second;
  }
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    Tri t;
    for (int k = 0; k < 3; ++k) {
      const uint32_t m = mesh.indices[i + size_t(k)];
      t.v[size_t(k)] = vertex[m];
      const Vec3d n =
          mesh.normals.empty() ? Vec3d{0, 0, 0} : normal_from_object.vector(Vec3d(mesh.normals[m]));
      t.n[size_t(k)] = n;
    }
    if (t.v[0] == t.v[1] || t.v[1] == t.v[2] || t.v[2] == t.v[0]) continue;
    const Vec3d face = unit_or(
        cross(positions_[t.v[1]] - positions_[t.v[0]], positions_[t.v[2]] - positions_[t.v[0]]),
        {0, 0, 1});
    for (size_t k = 0; k < 3; ++k) {
      t.n[k] = unit_or(t.n[k], mirrored ? -face : face);
      normals_[t.v[k]] += t.n[k];
    }
    if (mirrored) std::swap(t.v[1], t.v[2]), std::swap(t.n[1], t.n[2]);
    mesh_.push_back(t);
  }
  // A vertex's own normal (for its label) is its corners' mean: outward at sharp corners too.
  for (Vec3d& n : normals_)
    n = unit_or(n, {0, 0, 1});
}

uint32_t Trimmer::midpoint(uint32_t a, uint32_t b, Vec3d na, Vec3d nb) {
  const auto [it, added] = midpoints_.try_emplace(edge_key(a, b), 0);
  if (!added) return it->second;
  const Vec3d pa = positions_[a], pb = positions_[b];
  const CsgProbe::SurfacePoint p = surface_at((pa + pb) * 0.5, unit_or(na + nb, na));
  it->second = add_vertex(p.position, p.normal, TrimmedSurface::kNoPartner);
  return it->second;
}

Trimmer::Found Trimmer::bisect(Vec3d a, Vec3d b, Vec3d na, Vec3d nb, int from) {
  const double len = length(b - a);
  double lo = 0, hi = 1;
  CsgProbe::SurfacePoint at_lo{a, na}, at_hi{b, nb}, mid{a, na};
  for (int i = 0; i < 64 && (hi - lo) * len > kBisectionPrecision * tolerance_; ++i) {
    const double s = 0.5 * (lo + hi);
    mid = surface_at(a + (b - a) * s, unit_or(na * (1 - s) + nb * s, na));
    if (label_at(mid) == from)
      lo = s, at_lo = mid;
    else
      hi = s, at_hi = mid;
  }
  const size_t partner = probe_.boundary_between(at_lo, at_hi, leaf_, kLabelOffset * tolerance_);
  return {mid, 0.5 * (lo + hi),
          partner == CsgProbe::kNone ? TrimmedSurface::kNoPartner : uint32_t(partner)};
}

Trimmer::Crossing Trimmer::crossing(uint32_t a, uint32_t b, Vec3d na, Vec3d nb) {
  const bool forward = a < b;
  const auto it = crossings_.find(edge_key(a, b));
  if (it != crossings_.end()) return {it->second.vertex, forward ? it->second.s : 1 - it->second.s};
  const Found f = bisect(positions_[a], positions_[b], na, nb, label(a));
  // A crossing at a vertex is the vertex: it lies on the other boundary (two solids touching
  // there), and the piece cut off would have no size.
  const double at_vertex = kAtVertex * tolerance_ / length(positions_[b] - positions_[a]);
  Crossing found{a, 0};
  if (f.s >= 1 - at_vertex)
    found = {b, 1};
  else if (f.s > at_vertex)
    found = {add_vertex(f.point.position, f.point.normal, f.partner), f.s};
  // The vertex is then on the seam too.
  if (partners_[found.vertex] == TrimmedSurface::kNoPartner) partners_[found.vertex] = f.partner;
  crossings_[edge_key(a, b)] = {found.vertex, forward ? found.s : 1 - found.s};
  return found;
}

// The edge (k, k + 1) that longest-edge bisection splits: the longest, ties broken by the vertex
// indices, so that both triangles of an edge agree on it.
int Trimmer::longest_edge(const Tri& t) const {
  int best = 0;
  std::pair<double, uint64_t> longest{-1, 0};
  for (int k = 0; k < 3; ++k) {
    const uint32_t a = t.v[size_t(k)], b = t.v[size_t((k + 1) % 3)];
    const std::pair<double, uint64_t> key{length(positions_[b] - positions_[a]), edge_key(a, b)};
    if (key > longest) longest = key, best = k;
  }
  return best;
}

// Rivara's longest-edge bisection: a triangle with split edges (its longest among them) is
// halved at its longest edge, and each half again at its other split edge, if any.
void Trimmer::subdivide(const Tri& t, std::vector<Tri>& out) {
  const size_t k = size_t(longest_edge(t)), j = (k + 1) % 3, i = (k + 2) % 3;
  const auto it = midpoints_.find(edge_key(t.v[k], t.v[j]));
  if (it == midpoints_.end()) {
    out.push_back(t);
    return;
  }
  const uint32_t m = it->second;
  const Vec3d nm = corner_normal(m, t.n[k], t.n[j], 0.5);
  const auto halve = [&](const Tri& half, size_t split) {  // at edge (split, split + 1), if split
    const size_t a = split, b = (split + 1) % 3, c = (split + 2) % 3;
    const auto mid = midpoints_.find(edge_key(half.v[a], half.v[b]));
    if (mid == midpoints_.end()) {
      out.push_back(half);
      return;
    }
    const Vec3d n = corner_normal(mid->second, half.n[a], half.n[b], 0.5);
    out.push_back({{half.v[a], mid->second, half.v[c]}, {half.n[a], n, half.n[c]}});
    out.push_back({{mid->second, half.v[b], half.v[c]}, {n, half.n[b], half.n[c]}});
  };
  halve({{t.v[i], t.v[k], m}, {t.n[i], t.n[k], nm}}, 0);  // its other edge: (i, k)
  halve({{t.v[j], t.v[i], m}, {t.n[j], t.n[i], nm}}, 0);  // its other edge: (j, i)
}

// How far the straight cut across a triangle strays from the true crossing curve. `lone` is the
// corner whose label the other two do not share.
double Trimmer::cut_error(const Tri& t, int lone) {
  const size_t a = size_t(lone), b = (a + 1) % 3, c = (a + 2) % 3;
  const Crossing ab = crossing(t.v[a], t.v[b], t.n[a], t.n[b]);
  const Crossing ac = crossing(t.v[a], t.v[c], t.n[a], t.n[c]);
  const Vec3d cut_middle = (positions_[ab.vertex] + positions_[ac.vertex]) * 0.5;
  // The line from the lone corner through the middle of the flat cut meets the opposite edge at
  // q, with weights s1 / (s1 + s2) and s2 / (s1 + s2) on b and c.
  // Both crossings at the lone corner: the boundary passes through it, and there is nothing to cut.
  if (!(ab.s + ac.s > 0)) return 0;
  const Vec3d pa = positions_[t.v[a]], pb = positions_[t.v[b]], pc = positions_[t.v[c]];
  const double wb = ab.s / (ab.s + ac.s), wc = 1 - wb;
  const Vec3d q = pb * wb + pc * wc, nq = unit_or(t.n[b] * wb + t.n[c] * wc, t.n[b]);
  const int other = label(t.v[b]);
  // The boundary must cross that line once: anything else is a curve the cut cannot follow.
  if (label_at(surface_at(q, nq)) != other) return HUGE_VAL;
  const Found f = bisect(pa, q, t.n[a], nq, label(t.v[a]));
  return length(f.point.position - cut_middle);
}

// Whether the labels differ on the two sides of where another primitive's tessellation crosses
// the surface, looking a little farther than that tessellation strays from its own surface, then
// 4, 16 and 64 times as far within the triangle's size (where two surfaces meet at a shallow
// angle, the tessellations cross far from where the surfaces do): a boundary the set does not
// care about there (a plane far from what it cuts, a face ending on a face) cuts nothing.
bool Trimmer::cuts(const std::array<Vec3d, 2>& segment, Vec3d face, double size) {
  const Vec3d across = cross(face, segment[1] - segment[0]);
  if (!(length(across) > 0)) return false;  // touching at a point
  const Vec3d middle = (segment[0] + segment[1]) * 0.5, unit = normalize(across);
  for (double step = beside_; step == beside_ || step <= size; step *= 4) {
    if (step > 64 * beside_) break;
    if (label_at(surface_at(middle + unit * step, face)) !=
        label_at(surface_at(middle - unit * step, face)))
      return true;
  }
  return false;
}

bool Trimmer::needs_refinement(const Tri& t) {
  const Vec3d p[3] = {positions_[t.v[0]], positions_[t.v[1]], positions_[t.v[2]]};
  const double longest = std::max({length(p[1] - p[0]), length(p[2] - p[1]), length(p[0] - p[2])});
  if (longest <= tolerance_) return false;  // any error inside it is below the tolerance
  std::array<uint32_t, 3> key = t.v;
  std::sort(key.begin(), key.end());
  if (const auto it = verdicts_.find(key); it != verdicts_.end()) return it->second;

  const int l[3] = {label(t.v[0]), label(t.v[1]), label(t.v[2])};
  Bounds3d box;
  for (const Vec3d& q : p)
    box.extend(q);
  box.lo = box.lo - Vec3d{tolerance_, tolerance_, tolerance_};
  box.hi = box.hi + Vec3d{tolerance_, tolerance_, tolerance_};
  candidates_.clear();
  boundaries_.overlapping(box, candidates_);
  const std::array<Vec3d, 3> flat{p[0], p[1], p[2]};
  uint32_t first_other = TrimmedSurface::kNoPartner;
  bool two_others = false;
  // Where other boundaries cross the triangle: a crossing all within the tolerance of one point
  // hides nothing farther than that from the true crossing curve.
  Bounds3d crossings;
  const Vec3d face = unit_or(cross(p[1] - p[0], p[2] - p[0]), t.n[0]);
  for (const TaggedTriangle* other : candidates_) {
    if (other->tag == leaf_) continue;
    const auto segment = crossing_segment(flat, other->p);
    if (!segment || !cuts(*segment, face, longest)) continue;
    crossings.extend((*segment)[0]);
    crossings.extend((*segment)[1]);
    if (first_other == TrimmedSurface::kNoPartner) first_other = other->tag;
    two_others |= other->tag != first_other;
  }
  bool refine;
  if (l[0] == l[1] && l[1] == l[2])
    refine = !crossings.empty() && length(crossings.hi - crossings.lo) > 2 * tolerance_;
  else if (l[0] != l[1] && l[1] != l[2] && l[2] != l[0])
    refine = true;
  else
    refine = two_others || cut_error(t, lone_corner(l)) > tolerance_;
  verdicts_[key] = refine;
  return refine;
}

void Trimmer::refine() {
  for (int level = 0; level < kMaxLevels; ++level) {
    bool any = false;
    for (const Tri& t : mesh_)
      if (needs_refinement(t)) {
        const size_t k = size_t(longest_edge(t)), j = (k + 1) % 3;
        midpoint(t.v[k], t.v[j], t.n[k], t.n[j]);
        any = true;
      }
    if (!any) return;
    // Closure: a triangle with a split edge has its longest split too, so that halving it at the
    // longest keeps every split edge shared by both its triangles.
    for (bool changed = true; changed;) {
      changed = false;
      for (const Tri& t : mesh_) {
        const size_t k = size_t(longest_edge(t)), j = (k + 1) % 3;
        if (is_split(t.v[k], t.v[j])) continue;
        if (is_split(t.v[j], t.v[(j + 1) % 3]) || is_split(t.v[(j + 1) % 3], t.v[k])) {
          midpoint(t.v[k], t.v[j], t.n[k], t.n[j]);
          changed = true;
        }
      }
    }
    std::vector<Tri> next;
    next.reserve(2 * mesh_.size());
    for (const Tri& t : mesh_)
      subdivide(t, next);
    mesh_.swap(next);
  }
}

void Trimmer::emit(uint32_t a, uint32_t b, uint32_t c, Vec3d na, Vec3d nb, Vec3d nc, int label,
                   TrimmedSurface& out) const {
  if (label == 0 || a == b || b == c || c == a) return;
  if (label > 0)
    out.triangles.push_back({{a, b, c}, {na, nb, nc}});
  else  // the set lies outside the primitive here: its surface faces the other way
    out.triangles.push_back({{a, c, b}, {-na, -nc, -nb}});
}

TrimmedSurface Trimmer::cut() {
  TrimmedSurface out;
  for (const Tri& t : mesh_) {
    const int l[3] = {label(t.v[0]), label(t.v[1]), label(t.v[2])};
    if (l[0] == l[1] && l[1] == l[2]) {
      emit(t.v[0], t.v[1], t.v[2], t.n[0], t.n[1], t.n[2], l[0], out);
      continue;
    }
    if (l[0] != l[1] && l[1] != l[2] && l[2] != l[0]) {
      // Three regions meet in a triangle no longer than the tolerance: each corner keeps the
      // quadrilateral from its corner to the middle.
      std::array<Crossing, 3> e;
      std::array<Vec3d, 3> en;
      for (size_t k = 0; k < 3; ++k) {
        const size_t j = (k + 1) % 3;
        e[k] = crossing(t.v[k], t.v[j], t.n[k], t.n[j]);
        en[k] = corner_normal(e[k].vertex, t.n[k], t.n[j], e[k].s);
      }
      const Vec3d mean = unit_or(t.n[0] + t.n[1] + t.n[2], t.n[0]);
      const Vec3d centroid =
          (positions_[t.v[0]] + positions_[t.v[1]] + positions_[t.v[2]]) * (1.0 / 3);
      const CsgProbe::SurfacePoint s = surface_at(centroid, mean);
      const uint32_t m = add_vertex(s.position, s.normal, TrimmedSurface::kNoPartner);
      const Vec3d nm = corner_normal(m, mean, mean, 0);
      for (size_t k = 0; k < 3; ++k) {
        const size_t i = (k + 2) % 3;  // the edge before corner k
        emit(t.v[k], e[k].vertex, m, t.n[k], en[k], nm, l[k], out);
        emit(t.v[k], m, e[i].vertex, t.n[k], nm, en[i], l[k], out);
      }
      continue;
    }
    const size_t a = size_t(lone_corner(l));
    const size_t b = (a + 1) % 3, c = (a + 2) % 3;
    const Crossing ab = crossing(t.v[a], t.v[b], t.n[a], t.n[b]);
    const Crossing ac = crossing(t.v[a], t.v[c], t.n[a], t.n[c]);
    const Vec3d nab = corner_normal(ab.vertex, t.n[a], t.n[b], ab.s);
    const Vec3d nac = corner_normal(ac.vertex, t.n[a], t.n[c], ac.s);
    emit(t.v[a], ab.vertex, ac.vertex, t.n[a], nab, nac, l[a], out);
    emit(ab.vertex, t.v[b], t.v[c], nab, t.n[b], t.n[c], l[b], out);
    emit(ab.vertex, t.v[c], ac.vertex, nab, t.n[c], nac, l[b], out);
  }
  out.positions = positions_;
  out.partner = partners_;
  return out;
}

}  // namespace

TrimmedSurface trim_surface(const CsgProbe& probe, size_t leaf, const TriangleMesh& mesh,
                            const TriangleBvh& boundaries, const TrimTolerances& tolerances) {
  Trimmer trimmer(probe, leaf, boundaries, tolerances);
  trimmer.load(mesh);
  trimmer.refine();
  return trimmer.cut();
}

}  // namespace fb
