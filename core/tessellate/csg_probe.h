// A solid's set point by point, for tessellating CSG (core/tessellate/tessellate_csg.h): on which
// side of each primitive a point lies, whether a point of one primitive's boundary is surface of
// the whole set (and which way the set's normal points there), and the primitive's exact surface
// near a point. Every query goes through the renderer's own intersector
// (core/accel/solid_intersect.h), so any primitive the renderer intersects can be probed, and the
// mesh agrees with the render.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <filmback/vec.h>

#include "core/accel/solid_intersect.h"
#include "core/scene/solid.h"

namespace fb {

class CsgProbe {
 public:
  static constexpr size_t kNone = SIZE_MAX;

  // Throws InputError when a primitive's placement cannot be inverted (as the render would).
  explicit CsgProbe(const Solid& solid);

  // The primitives of the tree, depth first.
  size_t leaf_count() const { return leaves_.size(); }
  const Solid& leaf(size_t i) const { return *leaves_[i].solid; }
  // False for a primitive under `bounds_only` (a clip): it limits the set but is no surface.
  bool is_surface(size_t i) const { return leaves_[i].surface; }

  // For a point on the boundary of primitive `leaf`, with the primitive's outward normal there:
  // +1 when that boundary is surface of the set there with the set on the primitive's inner side
  // (the normal is the primitive's), -1 when the set lies on its outer side (the normal is
  // reversed: a difference's cut), 0 when it is no surface of the set. The set is evaluated
  // `offset` inside the surface with the primitive taken as inside, and as far outside with it
  // taken as outside: surface is where the two differ. Both points also move by half the offset
  // along one fixed direction oblique to every axis (a simulation of simplicity, Edelsbrunner and
  // Muecke 1990): boundaries that coincide there (coplanar faces, a face ending on another, solids
  // touching) are then all decided one way, as the set just beside them is.
  int label(Vec3d point, Vec3d normal, size_t leaf, double offset) const;

  struct SurfacePoint {
    Vec3d position, normal;  // world; the primitive's outward unit normal
  };

  // A primitive other than `leaf` whose side differs between the points label() looks at for a
  // and for b (inside the surface, else outside it), or kNone: where a label changes, the
  // primitive whose boundary passes there.
  size_t boundary_between(const SurfacePoint& a, const SurfacePoint& b, size_t leaf,
                          double offset) const;
  // The point of primitive `leaf`'s boundary on the line point + t direction (|t| <= reach) that
  // is nearest to `point`, or nothing when the line does not cross the boundary within reach.
  std::optional<SurfacePoint> lift(size_t leaf, Vec3d point, Vec3d direction, double reach) const;

 private:
  struct Leaf {
    const Solid* solid;
    RenderSolid set;  // the primitive's set alone, all of its boundary surface
    bool surface;
  };
  struct Node {
    SolidKind kind;
    bool inverse;
    size_t leaf = kNone;           // a primitive
    std::vector<size_t> children;  // a set operation: indices into nodes_
  };
  size_t add(const Solid& solid, bool surface);
  // The points label() looks at: inside the surface, then outside it.
  static std::array<Vec3d, 2> sides(const SurfacePoint& p, double offset);
  // Membership of the set below `node` with `forced` decided as `forced_in`; memo caches the
  // other leaves' memberships (-1: not asked yet).
  bool contains(size_t node, Vec3d p, size_t forced, bool forced_in,
                std::vector<int8_t>& memo) const;

  std::vector<Leaf> leaves_;
  std::vector<Node> nodes_;  // nodes_[0] is the root
};

}  // namespace fb
