#include "core/tessellate/triangle_bvh.h"

#include <algorithm>
#include <cmath>

namespace fb {

namespace {

constexpr uint32_t kLeafSize = 4;

Bounds3d bounds_of(const TaggedTriangle& t) {
  Bounds3d b;
  for (const Vec3d& p : t.p)
    b.extend(p);
  return b;
}

bool overlap(const Bounds3d& a, const Bounds3d& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
         a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

// Where segment [q0, q1] crosses triangle v (Moeller and Trumbore 1997, "Fast, minimum storage
// ray-triangle intersection", with the ray's parameter kept within the segment).
std::optional<Vec3d> segment_hit(Vec3d q0, Vec3d q1, const std::array<Vec3d, 3>& v) {
  const Vec3d e1 = v[1] - v[0], e2 = v[2] - v[0], d = q1 - q0;
  const Vec3d pvec = cross(d, e2);
  const double det = dot(e1, pvec);
  // Parallel, to the precision the edge vectors carry.
  if (!(std::abs(det) > 1e-14 * length(e1) * length(e2) * length(d))) return std::nullopt;
  const Vec3d s = q0 - v[0];
  const double u = dot(s, pvec) / det;
  if (u < 0 || u > 1) return std::nullopt;
  const Vec3d qvec = cross(s, e1);
  const double w = dot(d, qvec) / det;
  if (w < 0 || u + w > 1) return std::nullopt;
  const double t = dot(e2, qvec) / det;
  if (t < 0 || t > 1) return std::nullopt;
  return q0 + d * t;
}

}  // namespace

TriangleBvh::TriangleBvh(std::vector<TaggedTriangle> triangles) : triangles_(std::move(triangles)) {
  if (!triangles_.empty()) build(0, uint32_t(triangles_.size()));
}

// Median split on the centroids along the widest axis of their bounds.
uint32_t TriangleBvh::build(uint32_t first, uint32_t count) {
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.emplace_back();
  Bounds3d bounds, centres;
  for (uint32_t i = first; i < first + count; ++i) {
    const Bounds3d b = bounds_of(triangles_[i]);
    bounds.extend(b);
    centres.extend((b.lo + b.hi) * 0.5);
  }
  nodes_[index].bounds = bounds;
  if (count <= kLeafSize) {
    nodes_[index].first = first, nodes_[index].count = count;
    return index;
  }
  const Vec3d extent = centres.hi - centres.lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const auto begin = triangles_.begin() + first, middle = begin + count / 2;
  std::nth_element(begin, middle, begin + count,
                   [axis](const TaggedTriangle& a, const TaggedTriangle& b) {
                     return a.p[0][axis] + a.p[1][axis] + a.p[2][axis] <
                            b.p[0][axis] + b.p[1][axis] + b.p[2][axis];
                   });
  build(first, count / 2);
  const uint32_t right = build(first + count / 2, count - count / 2);
  nodes_[index].right = right;
  return index;
}

void TriangleBvh::overlapping(const Bounds3d& box, std::vector<const TaggedTriangle*>& out) const {
  if (nodes_.empty()) return;
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!overlap(node.bounds, box)) continue;
    if (node.count > 0) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i)
        if (overlap(bounds_of(triangles_[i]), box)) out.push_back(&triangles_[i]);
      continue;
    }
    stack[top++] = uint32_t(&node - nodes_.data()) + 1;
    stack[top++] = node.right;
  }
}

std::optional<std::array<Vec3d, 2>> crossing_segment(const std::array<Vec3d, 3>& a,
                                                     const std::array<Vec3d, 3>& b) {
  // The crossing lies on the line where the planes meet: its ends are where an edge of one
  // triangle passes through the other.
  const Vec3d along = cross(cross(a[1] - a[0], a[2] - a[0]), cross(b[1] - b[0], b[2] - b[0]));
  std::optional<std::array<Vec3d, 2>> ends;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  const auto add = [&](const std::optional<Vec3d>& p) {
    if (!p) return;
    const double s = dot(*p, along);
    if (!ends) ends = std::array<Vec3d, 2>{*p, *p};
    if (s < lo) lo = s, (*ends)[0] = *p;
    if (s > hi) hi = s, (*ends)[1] = *p;
  };
  for (int i = 0; i < 3; ++i) {
    add(segment_hit(a[i], a[(i + 1) % 3], b));
    add(segment_hit(b[i], b[(i + 1) % 3], a));
  }
  return ends;
}

}  // namespace fb
