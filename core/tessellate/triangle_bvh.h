// Triangles in world space, each tagged with what it approximates, in a bounding volume hierarchy
// for box queries; and the segment where two triangles cross. Tessellating CSG
// (core/tessellate/csg_trim.h) asks them where other primitives' boundaries pass through a
// triangle.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <filmback/vec.h>

#include "core/math/bounds.h"

namespace fb {

struct TaggedTriangle {
  std::array<Vec3d, 3> p;
  uint32_t tag = 0;
};

class TriangleBvh {
 public:
  explicit TriangleBvh(std::vector<TaggedTriangle> triangles);

  // Appends to `out` the triangles whose bounds overlap `box`.
  void overlapping(const Bounds3d& box, std::vector<const TaggedTriangle*>& out) const;

 private:
  struct Node {
    Bounds3d bounds;
    uint32_t first = 0, count = 0;  // a leaf: triangles_[first, first + count)
    uint32_t right = 0;             // an inner node: its children are this + 1 and `right`
  };
  uint32_t build(uint32_t first, uint32_t count);

  std::vector<TaggedTriangle> triangles_;
  std::vector<Node> nodes_;
};

// The segment along which two triangles cross, or nothing when they do not (or lie in one plane:
// coplanar overlaps are not reported). A single touching point gives a segment of zero length.
std::optional<std::array<Vec3d, 2>> crossing_segment(const std::array<Vec3d, 3>& a,
                                                     const std::array<Vec3d, 3>& b);

}  // namespace fb
