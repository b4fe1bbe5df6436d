// POV-Ray's left-handed, +Y-up space to filmback's right-handed, +Y-up world: mirror z
// (docs/pov.md "Coordinates"). Points, directions and normals map by S = diag(1, 1, -1), a
// matrix M by S M S; one POV-Ray unit is one metre. The mirror reverses triangle winding.
#pragma once

#include <filmback/vec.h>

#include "core/math/transform.h"

namespace fb::pov {

inline Vec3d world_from_pov(Vec3d p) { return {p.x, p.y, -p.z}; }

// S as a transform: world_from_pov_space() * m * world_from_pov_space() converts a POV matrix.
inline Transform world_from_pov_space() { return Transform::scale({1, 1, -1}); }

inline Transform world_from_pov(const Transform& pov_matrix) {
  return world_from_pov_space() * pov_matrix * world_from_pov_space();
}

}  // namespace fb::pov
