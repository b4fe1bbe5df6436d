// Blender's Subdivision Surface modifier, as the add-on writes it:
// nodes[i].extensions.FILMBACK_blender.subdivision (docs/blender.md, "Subdivision").
#pragma once

#include <optional>
#include <string>

#include "core/scene/scene.h"
#include "core/scene/subdivision_surface.h"
#include "core/util/diagnostics.h"

namespace tinygltf {
class Model;
class Node;
class Value;
}  // namespace tinygltf

namespace fb::gltf {

// The cage and settings under `path`, checked (indices in range, faces of at least three distinct
// vertices, creases on cage edges with weights in [0, 1], finite positions and texture
// coordinates, UV maps of one coordinate per corner, face_primitives below `primitive_count`,
// bounded counts). Throws InputError naming `file`, the JSON path and what was expected. The
// surface's face_parts hold the faces' primitive indices; placement, name and parts are the
// caller's.
SubdivisionSurface read_subdivision(const tinygltf::Value& subdivision, const std::string& path,
                                    const std::string& file, size_t primitive_count);

// The node's subdivision surface when its FILMBACK_blender extension has one, placed at `world`
// and named after the node. Its parts are the materials of the mesh's primitives that its faces
// wear (face_primitives; without it, the first primitive's), kNoSubdivisionMaterial for a
// primitive without one (the caller substitutes its default), each with the cage UV maps its
// material reads (found by name as for a triangle mesh; unread maps are dropped). The node's glTF
// mesh is the triangulated cage, written for other viewers: the caller does not render it.
constexpr uint32_t kNoSubdivisionMaterial = 0xffffffffu;
std::optional<SubdivisionSurface> read_node_subdivision(
    const tinygltf::Model& model, const tinygltf::Node& node, const std::string& path,
    const Transform& world, uint32_t scene_node, const std::vector<Material>& materials,
    const std::string& file, Diagnostics& diagnostics);

}  // namespace fb::gltf
