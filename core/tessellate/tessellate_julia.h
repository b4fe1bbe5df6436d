// A julia fractal (core/math/julia_fractal.h) as triangles, for `filmback convert`: marching
// tetrahedra (marching_tetrahedra.h) over its bounding sphere's box, the vertices on the set's
// boundary, the normals the escaping iterate's gradient. docs/pov.md, "Julia fractal".
#pragma once

#include <cstdint>

#include "core/math/julia_fractal.h"
#include "core/scene/scene.h"

namespace fb {

// Appends the set's boundary, in its object space, to `mesh`: counter-clockwise seen from
// outside; `cells` on each side (clamped to 2 .. kMarchedMaxCells).
void tessellate_julia_fractal(const JuliaFractal& julia, uint32_t cells, TriangleMesh& mesh);

}  // namespace fb
