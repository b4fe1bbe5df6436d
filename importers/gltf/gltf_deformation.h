// FILMBACK_deformation on a node: the shapes an exporter evaluated for each of the node's mesh
// primitives at times over the shutter (Blender's depsgraph: armatures, shape keys, modifiers,
// geometry nodes), read as untrusted input into EvaluatedShapes (core/scene/mesh_deformation.h),
// which replace the node's skin and morph targets (docs/scenes.md, "Blender's evaluated
// deformation").
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/mesh_deformation.h"

namespace tinygltf {
class Model;
class Node;
class Value;
}  // namespace tinygltf

namespace fb::gltf {

// At most this many (vertex, time) positions per primitive, 2^24: 200 MB of positions and as much
// again for normals, checked against the accessors' counts before any is read.
constexpr size_t kMaxEvaluatedVertexSteps = size_t(1) << 24;

struct NodeDeformation {
  bool world_space = false;  // true: the shapes are in world space and the node does not place them
  std::vector<double> times_s;
  std::string path;  // of the extension, for messages
  const tinygltf::Value* primitives = nullptr;
};

// The node's FILMBACK_deformation, none when it has none: its times (1 to kMaxEvaluatedShapes,
// finite, increasing) and one entry per primitive of the node's mesh (`primitive_count`). Throws
// InputError naming the JSON path otherwise.
std::optional<NodeDeformation> read_node_deformation(const tinygltf::Node& node,
                                                     const std::string& node_path,
                                                     size_t primitive_count,
                                                     const std::string& file);

// Primitive `p`'s shapes: one positions accessor per time, and normals (one per time, or none),
// each VEC3 float, finite, of `vertex_count` values; normals of zero length are refused. Throws
// InputError naming the JSON path.
EvaluatedShapes read_evaluated_shapes(const tinygltf::Model& model, const NodeDeformation& node,
                                      size_t p, size_t vertex_count, const std::string& file);

}  // namespace fb::gltf
