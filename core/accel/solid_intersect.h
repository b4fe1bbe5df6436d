// Exact ray intersection of an analytic solid (core/scene/solid.h) by ray-interval CSG (Roth
// 1982): each primitive gives the spans of the ray inside it, found in its object space in double
// precision; the tree combines them by union, intersection and complement, and the hit is the
// first boundary of the combined spans after t_min that lies on a surface.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <filmback/vec.h>

#include "core/math/bounds.h"
#include "core/math/transform.h"
#include "core/scene/solid.h"

namespace fb {

struct SolidHit {
  double t = 0;
  Vec3d position;         // render space: origin + t direction
  Vec3d position_error;   // conservative, per axis, including rounding `position` to float
  Vec3d normal;           // render space, unit, out of the solid's set
  uint32_t material = 0;  // of the primitive whose surface was hit
};

// A solid placed in render space, ready to intersect.
class RenderSolid {
 public:
  // `reach` bounds what is unbounded (half-spaces): the solid's bounds() are its set's bounds
  // clipped to it. Throws InputError when a primitive's placement cannot be inverted, or when
  // the tree could give one ray more spans than the intersector holds (2^20).
  RenderSolid(const Solid& solid, const Transform& render_from_world, const Bounds3d& reach);
  ~RenderSolid();
  RenderSolid(RenderSolid&&) noexcept;

  // The first surface point with t in (t_min, t_max) and before the exit from bounds(), or none.
  // Deterministic: the same ray gives the same answer, and a hit before t_max is the one t_max =
  // infinity gives (the renderer intersects again, uncut, to fill a hit record). Allocates
  // nothing once a thread has met its largest tree (kStackSpans in the .cpp).
  std::optional<SolidHit> first_hit(Vec3d origin, Vec3d direction, double t_min,
                                    double t_max = HUGE_VAL) const;

  // Whether a render-space point lies in the solid's set (on its boundary: either answer). What
  // tessellates CSG asks it of each primitive (core/tessellate/csg_probe.h).
  bool contains(Vec3d point) const;

  const Bounds3d& bounds() const { return bounds_; }
  // Whether the set is bounded without `reach` (it then counts in the scene's bounds).
  bool bounded() const { return bounded_; }

  struct Node;

 private:
  std::vector<Node> root_;  // one node; a vector because Node is incomplete here
  Bounds3d bounds_;
  bool bounded_ = true;
  size_t spans_ = 0;  // the span buffer one ray needs: the root's spans and workspace
};

}  // namespace fb
