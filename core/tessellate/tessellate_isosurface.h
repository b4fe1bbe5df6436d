// An isosurface (core/scene/isosurface.h) as triangles, for `filmback convert`: marching
// tetrahedra over a grid spanning its container, each vertex found by bisection on a grid edge the
// set's boundary crosses, so that it lies on the surface (the function's level or, unless `open`,
// the container's wall); the mesh strays from the surface between its vertices, by about a cell's
// chord error. docs/pov.md, "Isosurface".
#pragma once

#include <cstdint>

#include "core/scene/isosurface.h"
#include "core/scene/scene.h"

namespace fb {

// The grid's cells on the container's longest side, at most: 128^3 cells, 2.1 million function
// samples, whatever the tolerance asks.
constexpr uint32_t kIsosurfaceMaxCells = 128;

// Appends the isosurface's boundary, in its object space, to `mesh`: counter-clockwise seen from
// outside, with the surface's normals (the gradient's direction, the container's on its wall).
// `cells` on the longest side (clamped to 2 .. kIsosurfaceMaxCells), cubes as near as may be.
void tessellate_isosurface(const Isosurface& iso, bool open, uint32_t cells, TriangleMesh& mesh);

}  // namespace fb
