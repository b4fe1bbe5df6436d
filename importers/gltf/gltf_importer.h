// glTF 2.0 (.gltf, .glb) into a Scene, through tinygltf. What is read and what is skipped with a
// warning is listed in docs/scenes.md; errors name the file and the JSON path.
#pragma once

#include <filesystem>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"

namespace fb {

// Lumens per watt at 555 nm: the constant Blender's exporter multiplies by (PBR_WATTS_TO_LUMENS),
// so dividing by it turns KHR_lights_punctual candela and lux back into W/sr and W/m^2.
constexpr double kLumensPerWatt = 683.0;

Scene import_gltf(const std::filesystem::path& file, Diagnostics& diagnostics);

}  // namespace fb
