// Blender's physical camera and shot settings, carried as glTF `extras` (the custom properties
// Blender's exporter writes with export_extras). glTF itself keeps only yfov and aspectRatio; the
// names and units are listed in docs/scenes.md, "Extras".
#pragma once

#include <string>

#include "core/scene/camera.h"
#include "core/scene/scene.h"

namespace tinygltf {
class Value;
}

namespace fb::gltf {

// Overrides the fields of `camera` that `extras` names; returns whether it named any. Throws
// InputError with the JSON path for a value of the wrong type or out of range.
bool apply_camera_extras(const tinygltf::Value& extras, const std::string& path,
                         const std::string& file, PhysicalCamera& camera);

ShotSettings read_shot_extras(const tinygltf::Value& extras, const std::string& path,
                              const std::string& file);

}  // namespace fb::gltf
