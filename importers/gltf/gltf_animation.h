// glTF node animation (glTF 2.0 §3.11, "Animations"): every channel that moves a node's
// translation, rotation or scale becomes a curve of the scene's NodeHierarchy, validated as
// untrusted input. Morph-target weights are skipped with a warning.
#pragma once

#include <cstdint>
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
// one timeline; a property animated twice keeps its first channel. Throws InputError naming the
// JSON path of what is wrong.
void read_animations(const tinygltf::Model& model, const std::string& file,
                     const std::vector<uint32_t>& scene_node, NodeHierarchy& hierarchy,
                     Diagnostics& diagnostics);

}  // namespace fb::gltf
