// The triangles of an extruded outline (SolidKind::kOutline): its curves flattened to a chord
// tolerance, walls between the slab's planes, and caps cut into trapezoids by the even-odd rule.
#pragma once

#include <cstdint>

#include "core/scene/scene.h"

namespace fb {

// Appends the surface of the SolidKind::kOutline primitive (linear or conic, `open`: no caps) to
// `mesh`: object space, outward counter-clockwise faces, the curves' normals at the vertices;
// every point within `error` of the surface, each segment in at most `most_pieces` chords.
void tessellate_outline(const Solid& primitive, double error, uint32_t most_pieces,
                        TriangleMesh& mesh);

}  // namespace fb
