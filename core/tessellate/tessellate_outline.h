// The triangles of an extruded outline (SolidKind::kOutline): its curves flattened to a chord
// tolerance, walls between z = 0 and z = 1, and caps cut into trapezoids by the even-odd rule.
#pragma once

#include <cstdint>

#include "core/scene/scene.h"

namespace fb {

// Appends the outline's surface to `mesh` (object space, outward counter-clockwise faces, flat
// wall normals per flattened piece): every point within `error` of the surface, each segment
// in at most `most_pieces` chords. `open`: no caps.
void tessellate_outline(const Outline& outline, bool open, double error, uint32_t most_pieces,
                        TriangleMesh& mesh);

}  // namespace fb
