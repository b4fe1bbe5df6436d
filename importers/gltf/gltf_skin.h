// glTF skins (glTF 2.0 §3.8, "Skins"; §3.7.3.1, JOINTS_n and WEIGHTS_n) read as untrusted input
// into a SkinBinding that the render poses (core/scene/mesh_deformation.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/mesh_deformation.h"
#include "core/util/diagnostics.h"

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace fb::gltf {

// At most this many JOINTS_n / WEIGHTS_n sets per primitive (32 influences per vertex): more
// than any exporter writes, and a bound on the per-vertex arrays a small file can ask for.
constexpr size_t kMaxSkinAttributeSets = 8;

// What a skinned primitive's binding is read from: the skin (`skin_ref` is the JSON path of the
// node's "skin" reference), the primitive and its vertex count.
struct SkinSource {
  int skin = -1;
  std::string skin_ref;
  const tinygltf::Primitive* primitive = nullptr;
  std::string primitive_path;
  size_t vertex_count = 0;
};

// The binding of `source`: joints mapped through `scene_node` (glTF node -> Scene::hierarchy),
// inverse bind matrices (identity when absent), and every JOINTS_n / WEIGHTS_n set the primitive
// has. Weights that do not sum to one are normalised with a warning naming the attribute;
// throws InputError naming the JSON path for a joint outside the skin, a joint that is not in
// the rendered scene, non-finite inverse bind matrices, negative weights or a vertex whose
// weights are all zero.
SkinBinding read_skin_binding(const tinygltf::Model& model, const SkinSource& source,
                              const std::vector<uint32_t>& scene_node, const std::string& file,
                              Diagnostics& diagnostics);

}  // namespace fb::gltf
