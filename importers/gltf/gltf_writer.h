// Writes an fb::Scene as glTF 2.0 (`filmback convert`): triangle meshes, metallic-roughness
// materials, KHR_lights_punctual lights and the cameras, with everything glTF has no place for in
// the FILMBACK_blender extension that importers/gltf reads back (docs/blender.md "What is
// carried"), so that rendering the written file gives the image of the original scene.
#pragma once

#include <filesystem>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"

namespace fb {

// Writes `file` (.gltf, its buffer embedded as a data: URI) through a temporary file renamed into
// place: a failure leaves nothing half-written. Analytic solids must be tessellated first.
// Throws InputError naming the file it could not write.
void write_gltf(const Scene& scene, const std::filesystem::path& file, Diagnostics& diagnostics);

}  // namespace fb
