// A glTF camera node as a SceneCamera. Its values come from one source taken whole, by precedence
// FILMBACK_blender > EXT_camera_physical > extras with the same names > the core projection
// (yfov/aspectRatio or xmag/ymag); a lower source fills only what the higher one cannot express,
// and each value keeps where it came from (docs/blender.md, "Cameras").
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
