// POV-Ray objects as filmback geometry (docs/pov.md, "Geometry"): analytic shapes and CSG become
// Scene::solids, intersected exactly; triangle objects become meshes. Everything is mirrored
// into filmback's right-handed world (pov_space.h).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"
#include "importers/pov/pov_scene.h"

namespace fb::pov {

// The material index for a texture and interior (pov_appearance's MaterialTable::material).
using MaterialFor = std::function<uint32_t(const Texture&, const std::optional<Interior>&)>;

// Appends every object of `pov` to `scene`. A top-level union is taken apart (POV-Ray renders
// all of its members' surfaces); merge, intersection, difference, inverse and clipped_by become
// solids. What cannot be converted (degenerate shapes, meshes inside CSG, no_image objects) is
// left out with a warning naming where it was written.
void convert_objects(const Scene& pov, const MaterialFor& material_for, fb::Scene& scene,
                     Diagnostics& diagnostics);

}  // namespace fb::pov
