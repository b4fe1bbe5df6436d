// Lights and world of a glTF file in Blender's units (docs/blender.md, "Lights and world"):
// nodes[i].extensions.FILMBACK_blender.light when present, else KHR_lights_punctual converted
// back from photometric units; scenes[i].extensions.FILMBACK_blender world colour and strength.
#pragma once

#include <cstdint>
#include <string>

#include "core/math/transform.h"
#include "core/scene/scene.h"
#include "core/util/diagnostics.h"

namespace tinygltf {
class Model;
class Node;
}  // namespace tinygltf

namespace fb::gltf {

// Adds the node's light to `scene`. KHR_lights_punctual candela and lux become W/sr and W/m^2
// through kLumensPerWatt (gltf_importer.h), undoing Blender's exporter in its default "Standard"
// lighting mode (cd = P / (4 pi) * 683, lux = S * 683).: a Light for point, spot and sun lights, an
// emissive mesh (one-sided, shining down the node's -Z) for an area light. FILMBACK_blender.light
// takes precedence over the node's KHR_lights_punctual light, which is then ignored. Throws
// InputError naming `file` and the JSON path for values out of range.
void read_node_light(const tinygltf::Model& model, const tinygltf::Node& node,
                     const std::string& path, const Transform& world, uint32_t scene_node,
                     const std::string& file, Scene& scene, Diagnostics& diagnostics);

// The world of scenes[index] (FILMBACK_blender extension, else the scene's extras with the same
// names): world_color times world_strength as Scene::background, and world_hdr_uri, an
// equirectangular image inside the scene's folder, times world_strength as Scene::environment.
void read_world(const tinygltf::Model& model, size_t index, const std::string& file, Scene& scene);

}  // namespace fb::gltf
