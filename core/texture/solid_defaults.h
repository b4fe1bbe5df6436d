// POV-Ray's defaults for a pattern that leaves its colours out (source/core/material/pattern.cpp),
// as evaluate_solid (solid_pattern.cpp, which defines these) renders them; the glTF writer's
// stand-in colour for other viewers (importers/gltf/gltf_povray_pattern.cpp) averages the same.
#pragma once

#include <vector>

#include "core/scene/solid_texture.h"

namespace fb::solid {

// The colour map of a value pattern without one.
const std::vector<SolidColourStop>& default_map(SolidPatternKind kind);
// The list patterns (checker, hexagon, brick): the value picks one of list_size() entries, and
// default_list_colour() stands in for an entry the pattern leaves out.
bool is_list(SolidPatternKind kind);
int list_size(SolidPatternKind kind);
SolidColour default_list_colour(SolidPatternKind kind, int index);

}  // namespace fb::solid
