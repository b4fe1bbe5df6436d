// Meshes drawn many times: EXT_mesh_gpu_instancing (Blender's glTF exporter writes it for
// instanced collections) and the bound on how many instances a file may make, so that a small
// hostile file cannot ask for 10^9 of them (docs/scenes.md, "Instances").
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/math/transform.h"

namespace tinygltf {
class Model;
class Node;
}  // namespace tinygltf

namespace fb::gltf {

// At most this many mesh instances per file (2^22, about 4.2 million): 740 MB of records in the
// scene (176 bytes each) and 4.3 GB in the render (core/render/memory_estimate.h), past what this
// 2-core machine renders, and far below the 10^9 a small hostile file could otherwise ask for
// (EXT_mesh_gpu_instancing's count, or thousands of primitives drawn by thousands of nodes). A
// file that makes more is refused, naming the JSON path that crossed the bound.
constexpr size_t kMaxInstances = size_t(1) << 22;

// Throws InputError at `where` when `existing` instances and `more` would exceed kMaxInstances.
void check_instance_count(size_t existing, size_t more, const std::string& file,
                          const std::string& where);

// The node's EXT_mesh_gpu_instancing placements, node_from_instance for each instance (its
// TRANSLATION, ROTATION and SCALE, each defaulting to identity), or nothing when the node has no
// such extension. The extension's count is checked against kMaxInstances given `existing`
// instances before any accessor is read; every accessor must hold that same count.
std::optional<std::vector<Transform>> read_gpu_instances(const tinygltf::Model& model,
                                                         const tinygltf::Node& node,
                                                         const std::string& node_path,
                                                         const std::string& file, size_t existing);

}  // namespace fb::gltf
