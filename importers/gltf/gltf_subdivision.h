// Blender's Subdivision Surface modifier, as the add-on writes it:
// nodes[i].extensions.FILMBACK_blender.subdivision (docs/blender.md, "Subdivision").
#pragma once

#include <optional>
#include <string>

#include "core/scene/subdivision_surface.h"

namespace tinygltf {
class Model;
class Node;
class Value;
}  // namespace tinygltf

namespace fb::gltf {

// The cage and settings under `path`, checked (indices in range, faces of at least three distinct
// vertices, creases on cage edges with weights in [0, 1], finite positions, bounded counts).
// Throws InputError naming `file`, the JSON path and what was expected. Placement, name and
// material are the caller's.
SubdivisionSurface read_subdivision(const tinygltf::Value& subdivision, const std::string& path,
                                    const std::string& file);

// The node's subdivision surface when its FILMBACK_blender extension has one, placed at `world`
// and named after the node. Its material is that of the mesh's first primitive, or
// kNoSubdivisionMaterial when that has none (the caller substitutes its default). The node's glTF
// mesh is the triangulated cage, written for other viewers: the caller does not render it.
constexpr uint32_t kNoSubdivisionMaterial = 0xffffffffu;
std::optional<SubdivisionSurface> read_node_subdivision(const tinygltf::Model& model,
                                                        const tinygltf::Node& node,
                                                        const std::string& path,
                                                        const Transform& world, uint32_t scene_node,
                                                        const std::string& file);

}  // namespace fb::gltf
