// glTF materials (metallic-roughness core, KHR_materials_emissive_strength, _transmission, _ior,
// _specular, KHR_texture_transform) into filmback's Material, and the per-vertex data their
// textures read (TEXCOORD_n, TANGENT or tangents computed from the texture coordinates).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"
#include "importers/gltf/gltf_accessors.h"
#include "importers/gltf/gltf_blender_material.h"
#include "importers/gltf/gltf_json.h"

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace fb::gltf {

// model.materials into scene.materials, index for index, and model.images into scene.images
// (their encoded bytes are moved out of the model), then the images Blender materials' shader
// graphs name (FILMBACK_blender, gltf_blender_material.h). Bad values throw an InputError naming
// the JSON path; what is not carried is a warning.
void read_materials(tinygltf::Model& model, const std::string& file, Scene& scene,
                    Diagnostics& diagnostics);

// Which TEXCOORD_n fills each texture-coordinate slot of a mesh (VertexTextureData::texcoords) for
// `material`, and from which slot's coordinates normal maps' tangents come. A shader graph's UV
// maps are found by name in `maps` (one the mesh lacks is a warning naming `path`, and reads
// TEXCOORD_0); glTF textures read TEXCOORD_n in slot n, and a set a texture reads is required.
// Shared by triangle primitives and subdivision cages, whose UV map n stands for TEXCOORD_n.
struct TexcoordPlan {
  std::array<std::optional<uint32_t>, VertexTextureData::kSets> slots;
  std::array<bool, VertexTextureData::kSets> required{};
  std::optional<uint32_t> tangent_slot;
};
TexcoordPlan plan_texcoords(const Material& material, const MeshUvMaps& maps,
                            const std::string& file, const std::string& path,
                            Diagnostics& diagnostics);

// The texture coordinates and tangents `material` reads, into mesh.texturing. `path` is the
// primitive's JSON path. Tangents come from TANGENT, or are computed per vertex from the
// triangles' texture-coordinate gradients when the material has a normal map and the file none.
// A shader graph's UV maps are found by name in `mesh_extension` (the mesh's FILMBACK_blender).
void read_texturing(const AccessorContext& ctx, const tinygltf::Primitive& prim,
                    const std::string& path, const Material& material, const Fields& mesh_extension,
                    TriangleMesh& mesh, Diagnostics& diagnostics);

}  // namespace fb::gltf
