// Ray and point queries on one object while the scene is parsed: what POV-Ray's trace(),
// inside(), min_extent() and max_extent() ask (POV-Ray 3.7 reference, "Functions"; docs/pov.md,
// "Object queries"). The object is converted as the render converts it (pov_geometry) and asked
// with the render's own intersection code: its solids one by one (RenderSolid, exact, in double
// precision), its triangles through an Embree BVH (RenderGeometry). Everything is in POV-Ray's
// own space, where the scene's expressions live.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <filmback/vec.h>

#include "core/accel/render_geometry.h"
#include "core/accel/solid_intersect.h"
#include "core/math/bounds.h"
#include "core/scene/scene.h"
#include "importers/pov/pov_scene.h"

namespace fb::pov::sdl {

// What POV-Ray gives for a side of a bounding box that has no end (BOUND_HUGE / 2).
constexpr double kPovUnboundedExtent = 1e10;

struct ProbeHit {
  Vec3d position;  // POV-Ray space
  Vec3d normal;    // unit: out of a solid's set; on a triangle, towards the ray's origin
};

class ObjectProbe {
 public:
  // Throws fb::InputError when a solid cannot be intersected (RenderSolid's limits).
  explicit ObjectProbe(const Object& object);
  ~ObjectProbe();
  ObjectProbe(const ObjectProbe&) = delete;
  ObjectProbe& operator=(const ObjectProbe&) = delete;

  // The first surface point along the ray from `origin` in `direction` (any length but zero).
  std::optional<ProbeHit> trace(Vec3d origin, Vec3d direction) const;
  // Whether `point` lies in a solid's set. Triangles have no inside here (docs/pov.md).
  bool inside(Vec3d point) const;
  // POV-Ray-space box of the object as POV-Ray bounds it: each primitive's box through its
  // transform, an intersection within its children's; unbounded sides at kPovUnboundedExtent.
  // Empty when nothing of the object could be converted.
  const Bounds3d& bounds() const { return bounds_; }
  bool has_triangles() const { return triangles_ != nullptr; }

 private:
  fb::Scene scene_;  // the converted object; outlives `triangles_`, which reads it
  std::vector<RenderSolid> solids_;
  std::unique_ptr<RenderGeometry> triangles_;
  Bounds3d bounds_;
};

}  // namespace fb::pov::sdl
