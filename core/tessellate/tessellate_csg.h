// Any solid, CSG included, as triangles (`filmback convert`; docs/architecture.md "Solids"): each
// primitive that carries surface is tessellated (core/tessellate/tessellate.h), trimmed to the part
// the render shows of it, with the render's normal and the primitive's material
// (core/tessellate/csg_trim.h), and the pieces are joined along their seams
// (core/tessellate/seam_join.h).
#pragma once

#include <vector>

#include "core/scene/scene.h"
#include "core/tessellate/tessellate.h"
#include "core/util/diagnostics.h"

namespace fb {

struct SolidTessellation {
  // A translation to the middle of the meshes: their float vertices keep their precision, and
  // vertices the pieces share along seams are the same floats, so the seams stay closed.
  Transform world_from_mesh;
  std::vector<TriangleMesh> meshes;  // one per material, named after the solid
};

// Surfaces lie within their primitive's tolerance (tessellation_tolerance_m), and cuts within the
// smallest tolerance of the solid's bounded primitives of the true crossing curves. A primitive
// with no tessellation yet (a polynomial) is reported: its surface is left out. Throws InputError
// when a primitive's placement cannot be inverted.
SolidTessellation tessellate_csg(const Solid& solid, const TessellationOptions& options,
                                 Diagnostics& diagnostics);

}  // namespace fb
