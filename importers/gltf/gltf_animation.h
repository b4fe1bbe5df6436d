// glTF node animation (glTF 2.0 §3.11, "Animations"): every channel that moves a node's
// translation, rotation or scale becomes a curve of the scene's NodeHierarchy, validated as
// untrusted input; every channel that moves a node's morph target `weights` becomes a curve of that
// node's mesh (core/scene/mesh_deformation.h).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/scene/animation.h"
#include "core/util/diagnostics.h"

namespace tinygltf {
class Model;
}

namespace fb::gltf {

// `scene_node[i]` is the hierarchy index of glTF node i, or kNoNode when the rendered scene does
// not hold it (its channels then move nothing and are ignored). All animations play together on
// one timeline; a property animated twice keeps its first channel. `morph_weights` receives the
// `weights` curves by glTF node index, one weight per morph target of the node's mesh. Throws
// InputError naming the JSON path of what is wrong.
void read_animations(const tinygltf::Model& model, const std::string& file,
                     const std::vector<uint32_t>& scene_node, NodeHierarchy& hierarchy,
                     std::map<size_t, AnimationCurve>& morph_weights, Diagnostics& diagnostics);

}  // namespace fb::gltf
