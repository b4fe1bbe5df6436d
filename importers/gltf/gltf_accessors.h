// Reading glTF accessors as untrusted data: every index, offset, stride and count is checked
// against the buffer it points into before a byte is read, and every message names the JSON
// path of the element that was wrong.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <filmback/vec.h>

namespace tinygltf {
class Model;
}

namespace fb::gltf {

struct AccessorContext {
  const tinygltf::Model& model;
  std::string file;  // for messages
};

// A VEC3 float accessor, each value finite. `where` is the referring JSON path.
std::vector<Vec3f> read_vec3(const AccessorContext& ctx, int accessor, const std::string& where);

// A SCALAR unsigned byte/short/int accessor, each value below `vertex_count`.
std::vector<uint32_t> read_indices(const AccessorContext& ctx, int accessor,
                                   const std::string& where, size_t vertex_count);

// A JOINTS_n attribute (glTF 2.0 §3.7.3.1): VEC4 of unsigned byte or short, four per vertex.
// The caller checks them against the skin's joint count.
std::vector<uint32_t> read_joint_indices(const AccessorContext& ctx, int accessor,
                                         const std::string& where);

// An animation sampler's accessor (glTF 2.0 §3.11), a texture coordinate, tangent or WEIGHTS_n
// attribute, or a skin's inverse bind matrices, as doubles, every component finite: of the given
// TINYGLTF_TYPE_*, float, or also normalized byte or short when `normalized_integers` (rotations,
// TEXCOORD_n and WEIGHTS_n may be stored so).
std::vector<double> read_animation_values(const AccessorContext& ctx, int accessor,
                                          const std::string& where, int type,
                                          bool normalized_integers);

}  // namespace fb::gltf
