// A Blender material's shader nodes from `materials[i].extensions.FILMBACK_blender` (written by
// filmback's add-on, docs/blender.md "Materials") into a ShaderGraph, and which TEXCOORD_n of a
// mesh holds each UV map the graph reads (`meshes[i].extensions.FILMBACK_blender.uv_maps`).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {

// The graph in `extension` (a material's FILMBACK_blender object). Image textures are appended to
// `scene.images` (files inside the scene's folder). Throws InputError naming the JSON path of a
// bad value; the add-on's own warnings about what it could not carry are passed on.
ShaderGraph read_shader_graph(const Fields& extension, Scene& scene, Diagnostics& diagnostics);

// The UV maps of a mesh in TEXCOORD order and its active render map, from its FILMBACK_blender
// extension (empty when the mesh has none: TEXCOORD_0 is then the active render map).
struct MeshUvMaps {
  std::vector<std::string> names;
  std::string active_render;
  // TEXCOORD index of the map `name` ("" is the active render map); nullopt when the mesh has no
  // such map.
  std::optional<uint32_t> texcoord(const std::string& name) const;
};
MeshUvMaps read_mesh_uv_maps(const Fields& mesh_extension);

// VertexTextureData::radial_tangents of a mesh's object-space positions (glTF axes), from the
// texture space its FILMBACK_blender extension carries (Blender's object axes), else from the
// positions' bounds (Blender's automatic texture space).
std::vector<Vec3f> radial_tangents(const std::vector<Vec3f>& positions,
                                   const Fields& mesh_extension);

}  // namespace fb::gltf
