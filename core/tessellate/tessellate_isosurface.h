// An isosurface (core/scene/isosurface.h) as triangles, for `filmback convert`: marching
// tetrahedra (marching_tetrahedra.h) over a grid spanning its container, the vertices on the
// function's level or, unless `open`, the container's wall. docs/pov.md, "Isosurface".
#pragma once

#include <cstdint>

#include "core/scene/isosurface.h"
#include "core/scene/scene.h"
#include "core/tessellate/marching_tetrahedra.h"

namespace fb {

// Appends the isosurface's boundary, in its object space, to `mesh`: counter-clockwise seen from
// outside, with the surface's normals (the gradient's direction, the container's on its wall).
// `cells` on the longest side (clamped to 2 .. kMarchedMaxCells), cubes as near as may be.
void tessellate_isosurface(const Isosurface& iso, bool open, uint32_t cells, TriangleMesh& mesh);

}  // namespace fb
