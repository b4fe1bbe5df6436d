#include "core/tessellate/tessellate_outline.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/scene/solid.h"
#include "core/util/error.h"

namespace fb {

namespace {

// Trapezoids both caps may take together, at most: a comb-shaped outline of n teeth cuts into
// about n^2 of them, which a hostile scene must not turn into gigabytes.
constexpr size_t kMaxOutlineCapTrapezoids = size_t(1) << 22;

double length_2d(Vec2d v) {
  return std::hypot(v.x, v.y);
}

// Chords keeping a segment within `error`: linear interpolation over a step h strays from a curve
// by at most h^2 max|B''| / 8, and |B''(u)| <= 2 |c2| + 6 |c3| on [0, 1].
uint32_t outline_chords(const OutlineSegment& s, double error, uint32_t most) {
  if (s.degree == 1) return 1;
  const double bend = 2 * length_2d(s.c[2]) + 6 * length_2d(s.c[3]);
  const double chords = std::ceil(std::sqrt(bend / (8 * error)));
  return chords >= 1 ? uint32_t(std::min(chords, double(most))) : 1;
}

// The unit normal at u pointing out of the set on `outward_sign`'s side of the tangent.
Vec2d outline_normal_at(const OutlineSegment& s, double u, double outward_sign) {
  const Vec2d t = segment_tangent(s, u);
  const double len = length_2d(t);
  return len > 0 ? Vec2d{t.y, -t.x} * (outward_sign / len) : Vec2d{0, 0};
}

// +1 when the tangent turned clockwise points out of the outline at the segment's middle, else
// -1: even-odd contours carry no orientation, so a point a little to that side is tested.
double outward_sign(const Outline& outline, const OutlineSegment& s) {
  const Vec2d n = outline_normal_at(s, 0.5, 1);
  const double step = 1e-7 * std::max(length_2d(outline.hi - outline.lo), 1e-300);
  return outline_contains(outline, segment_point(s, 0.5) + n * step) ? -1 : 1;
}

void add_vertex(TriangleMesh& mesh, Vec2d p, double z, Vec3d normal) {
  mesh.positions.emplace_back(Vec3d{p.x, p.y, z});
  mesh.normals.emplace_back(normal);
}

// One segment's wall: a strip of quads from z0 to z1, wound counter-clockwise seen from out.
void add_wall(const Outline& outline, const OutlineSegment& s, uint32_t chords, double z0,
              double z1, TriangleMesh& mesh, std::vector<Vec2d>& flattened) {
  const double sign = outward_sign(outline, s);
  const uint32_t base = uint32_t(mesh.positions.size());
  for (uint32_t k = 0; k <= chords; ++k) {
    const double u = double(k) / chords;
    const Vec2d p = k == 0 ? s.start : k == chords ? s.end : segment_point(s, u);
    const Vec2d n = outline_normal_at(s, u, sign);
    for (double z : {z0, z1})
      add_vertex(mesh, p, z, {n.x, n.y, 0});
    flattened.push_back(p);
  }
  // (a0, b0, b1) faces along (dy, -dx): the tangent turned clockwise.
  for (uint32_t k = 0; k < chords; ++k) {
    const uint32_t a0 = base + 2 * k, a1 = a0 + 1, b0 = a0 + 2, b1 = a0 + 3;
    if (sign > 0)
      mesh.indices.insert(mesh.indices.end(), {a0, b0, b1, a0, b1, a1});
    else
      mesh.indices.insert(mesh.indices.end(), {a0, b1, b0, a0, a1, b1});
  }
}

struct CapEdge {
  Vec2d low, high;  // low.y < high.y
  double x_at(double y) const {
    return low.x + (high.x - low.x) * ((y - low.y) / (high.y - low.y));
  }
};

// Both caps by a sweep in y: between two consecutive vertex heights no edge starts or ends, so
// the edges crossing that band, sorted by x, bound it inside and out in turn (even-odd): each
// pair is a trapezoid.
void add_caps(const std::vector<std::vector<Vec2d>>& contours, double z0, double z1,
              TriangleMesh& mesh) {
  std::vector<CapEdge> edges;
  std::vector<double> levels;
  for (const std::vector<Vec2d>& chain : contours)
    for (size_t i = 0; i + 1 < chain.size(); ++i) {
      Vec2d a = chain[i], b = chain[i + 1];
      if (a.y == b.y) continue;
      if (a.y > b.y) std::swap(a, b);
      edges.push_back({a, b});
      levels.push_back(a.y), levels.push_back(b.y);
    }
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  std::sort(edges.begin(), edges.end(),
            [](const CapEdge& a, const CapEdge& b) { return a.low.y < b.low.y; });
  std::vector<const CapEdge*> active;
  std::vector<std::pair<double, const CapEdge*>> band;
  size_t next = 0, trapezoids = 0;
  for (size_t k = 0; k + 1 < levels.size(); ++k) {
    const double y0 = levels[k], y1 = levels[k + 1];
    std::erase_if(active, [&](const CapEdge* e) { return e->high.y <= y0; });
    for (; next < edges.size() && edges[next].low.y <= y0; ++next)
      active.push_back(&edges[next]);
    band.clear();
    for (const CapEdge* e : active)
      band.push_back({0.5 * (e->x_at(y0) + e->x_at(y1)), e});
    std::sort(band.begin(), band.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    trapezoids += band.size() / 2;
    if (trapezoids > kMaxOutlineCapTrapezoids)
      throw InputError("an outline's caps need more than " +
                       std::to_string(kMaxOutlineCapTrapezoids) + " trapezoids: too intricate");
    for (size_t i = 0; i + 1 < band.size(); i += 2) {
      const CapEdge &left = *band[i].second, &right = *band[i + 1].second;
      const Vec2d corners[4] = {{left.x_at(y0), y0},
                                {right.x_at(y0), y0},
                                {right.x_at(y1), y1},
                                {left.x_at(y1), y1}};  // counter-clockwise seen from +z
      // Where the two edges meet (a vertex of the outline), a side has no length: one triangle.
      const bool bottom = corners[1].x > corners[0].x, top = corners[2].x > corners[3].x;
      for (double z : {z0, z1}) {
        const bool up = z == z1;  // the bottom cap faces -z: wound the other way
        const uint32_t base = uint32_t(mesh.positions.size());
        for (const Vec2d& c : corners)
          add_vertex(mesh, c, z, {0, 0, up ? 1.0 : -1.0});
        if (bottom)
          mesh.indices.insert(mesh.indices.end(), {base, base + (up ? 1 : 2), base + (up ? 2 : 1)});
        if (top)
          mesh.indices.insert(mesh.indices.end(), {base, base + (up ? 2 : 3), base + (up ? 3 : 2)});
      }
    }
  }
}

}  // namespace

void tessellate_outline(const Solid& primitive, double error, uint32_t most_pieces,
                        TriangleMesh& mesh) {
  const Outline& outline = *primitive.outline;
  const bool conic = primitive.conic;
  const double z0 = conic ? std::min(primitive.radius0, primitive.radius1) : 0;
  const double z1 = conic ? std::max(primitive.radius0, primitive.radius1) : 1;
  // A conic section at z is the outline scaled by z: its chords stray z times as far.
  const double section_error =
      conic ? error / std::max({std::abs(z0), std::abs(z1), 1e-300}) : error;
  const size_t first = mesh.positions.size();
  std::vector<std::vector<Vec2d>> flattened(outline.segments.size());
  for (size_t i = 0; i < outline.segments.size(); ++i) {
    const OutlineSegment& s = outline.segments[i];
    add_wall(outline, s, outline_chords(s, section_error, most_pieces), z0, z1, mesh, flattened[i]);
  }
  if (!primitive.open) add_caps(flattened, z0, z1, mesh);
  if (!conic) return;
  // The conic solid is the linear one mapped by F(x, y, z) = (z x, z y, z), whose Jacobian has
  // determinant z^2 > 0: the winding stays outward, normals go by the inverse transpose,
  // (n_x / z, n_y / z, n_z - (x n_x + y n_y) / z), here times |z| so that the apex (z = 0, where
  // the slab starts at it) keeps its walls' limit. The rulings are straight: exact between ends.
  for (size_t i = first; i < mesh.positions.size(); ++i) {
    const Vec3d p(mesh.positions[i]), n(mesh.normals[i]);
    const double side = p.z < 0 ? -1 : 1;
    const Vec3d mapped = Vec3d{n.x, n.y, n.z * p.z - (p.x * n.x + p.y * n.y)} * side;
    mesh.positions[i] = Vec3f(Vec3d{p.x * p.z, p.y * p.z, p.z});
    if (length(mapped) > 0) mesh.normals[i] = Vec3f(normalize(mapped));
  }
}

}  // namespace fb
