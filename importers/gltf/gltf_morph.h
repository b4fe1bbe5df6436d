// glTF morph targets (glTF 2.0 §3.7.2.2, "Morph Targets"): a primitive's POSITION, NORMAL and
// TANGENT displacements and the weights that mix them, read as untrusted input into MorphTargets
// that the render applies before skinning (core/scene/mesh_deformation.h).
#pragma once

#include <cstddef>
#include <string>

#include "core/scene/mesh_deformation.h"

namespace tinygltf {
class Model;
class Node;
class Mesh;
struct Primitive;
}  // namespace tinygltf

namespace fb::gltf {

// At most this many targets per primitive: far more than exporters write (Blender's shape keys
// are rarely more than a few hundred), and small enough that a file naming a million is refused
// before anything is read.
constexpr size_t kMaxMorphTargets = 1024;

// At most this many (vertex, target) displacements per primitive, 2^24: 200 MB of positions and
// as much again for normals, checked before any target's accessor is read.
constexpr size_t kMaxMorphDisplacements = size_t(1) << 24;

// The targets of `prim` (at `prim_path`) of `vertex_count` vertices, and their static weights:
// the node's `weights`, else the mesh's, else zeros. `has_tangents`: whether the mesh keeps
// tangents for TANGENT displacements to move. A target may lack any attribute. Throws InputError
// naming the JSON path for too many targets or displacements (before any target is read), a
// weights array of the wrong length or with a non-finite weight, and a displacement accessor whose
// count is not the vertex count.
MorphTargets read_morph_targets(const tinygltf::Model& model, const tinygltf::Node& node,
                                const std::string& node_path, const tinygltf::Mesh& mesh,
                                const tinygltf::Primitive& prim, const std::string& prim_path,
                                size_t vertex_count, bool has_tangents, const std::string& file);

}  // namespace fb::gltf
