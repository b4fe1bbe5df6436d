// A glTF camera node as a SceneCamera: the core projection (yfov/aspectRatio or xmag/ymag), then
// Blender's physical camera where the file carries it, by precedence FILMBACK_blender >
// EXT_camera_physical > extras with the same names (docs/blender.md, "Cameras").
#pragma once

#include <string>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"

namespace tinygltf {
class Model;
class Node;
}  // namespace tinygltf

namespace fb::gltf {

// `settings` are the scene's (its resolution fixes the image shape the camera was made for).
SceneCamera read_camera(const tinygltf::Model& model, const tinygltf::Node& node,
                        const std::string& path, const Transform& world, uint32_t scene_node,
                        const ShotSettings& settings, const std::string& file,
                        Diagnostics& diagnostics);

}  // namespace fb::gltf
