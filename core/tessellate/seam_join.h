// The trimmed surfaces of one CSG solid's primitives (core/tessellate/csg_trim.h) joined into one
// surface. Where two primitives' surfaces meet, each side has cut its triangles at its own points
// of the common crossing curve; each side's cut vertices are inserted into the other side's seam
// edges (a vertex lies within the tolerance of the other side's chord, and strictly between its
// ends), so that both sides end up with the same vertices along the seam: no T-junction, no crack,
// and a closed solid gives a closed mesh.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <filmback/vec.h>

#include "core/tessellate/csg_trim.h"

namespace fb {

struct SurfacePart {
  TrimmedSurface surface;
  uint32_t leaf = 0;      // the primitive (CsgProbe's leaf index)
  uint32_t material = 0;  // the primitive's
};

struct JoinedSurface {
  struct Triangle {
    std::array<uint32_t, 3> v;
    std::array<Vec3d, 3> n;
    uint32_t material;
  };
  std::vector<Vec3d> positions;  // world; some may be unused
  std::vector<Triangle> triangles;
};

JoinedSurface join_surfaces(const std::vector<SurfacePart>& parts, double tolerance_m);

}  // namespace fb
