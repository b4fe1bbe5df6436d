#include "importers/gltf/gltf_morph.h"

#include <tiny_gltf.h>

#include <cmath>

#include "core/util/error.h"
#include "importers/gltf/gltf_accessors.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {
namespace {

// The static weights: the node's override the mesh's (glTF 2.0 §3.7.2.2); each must have one
// per target.
std::vector<double> static_morph_weights(const tinygltf::Node& node, const std::string& node_path,
                                         const tinygltf::Mesh& mesh, const std::string& mesh_path,
                                         size_t targets, const std::string& file) {
  const bool on_node = !node.weights.empty();
  const std::vector<double>& weights = on_node ? node.weights : mesh.weights;
  if (weights.empty()) return std::vector<double>(targets, 0.0);
  const std::string where = (on_node ? node_path : mesh_path) + ".weights";
  if (weights.size() != targets)
    throw_input(file, where,
                std::to_string(weights.size()) + " weights for " + std::to_string(targets) +
                    " morph targets; expected one per target");
  for (size_t i = 0; i < weights.size(); ++i)
    if (!std::isfinite(weights[i]))
      throw_input(file, where + "[" + std::to_string(i) + "]", "not a finite number");
  return weights;
}

// One target's displacements of `name`, or none when the target has no such attribute.
std::vector<Vec3f> displacements(const AccessorContext& ctx,
                                 const std::map<std::string, int>& target, const char* name,
                                 const std::string& tpath, size_t vertex_count) {
  const auto it = target.find(name);
  if (it == target.end()) return {};
  const std::string where = tpath + "." + name;
  std::vector<Vec3f> out = read_vec3(ctx, it->second, where);
  if (out.size() != vertex_count)
    throw_input(ctx.file, where,
                std::to_string(out.size()) + " displacements for " + std::to_string(vertex_count) +
                    " positions");
  return out;
}

}  // namespace

MorphTargets read_morph_targets(const tinygltf::Model& model, const tinygltf::Node& node,
                                const std::string& node_path, const tinygltf::Mesh& mesh,
                                const tinygltf::Primitive& prim, const std::string& prim_path,
                                size_t vertex_count, bool has_tangents, const std::string& file) {
  const size_t targets = prim.targets.size();
  const std::string tpath = prim_path + ".targets";
  if (targets > kMaxMorphTargets)
    throw_input(file, tpath,
                std::to_string(targets) + " morph targets; expected at most " +
                    std::to_string(kMaxMorphTargets));
  if (vertex_count * targets > kMaxMorphDisplacements)
    throw_input(file, tpath,
                std::to_string(targets) + " morph targets of " + std::to_string(vertex_count) +
                    " vertices; expected at most " + std::to_string(kMaxMorphDisplacements) +
                    " displacements in all");
  const std::string mesh_path = index_path("meshes", size_t(&mesh - model.meshes.data()));
  MorphTargets out;
  out.weights = static_morph_weights(node, node_path, mesh, mesh_path, targets, file);
  const AccessorContext ctx{model, file};
  for (size_t t = 0; t < targets; ++t) {
    const std::string path = tpath + "[" + std::to_string(t) + "]";
    out.positions.push_back(displacements(ctx, prim.targets[t], "POSITION", path, vertex_count));
    out.normals.push_back(displacements(ctx, prim.targets[t], "NORMAL", path, vertex_count));
    out.tangents.push_back(has_tangents
                               ? displacements(ctx, prim.targets[t], "TANGENT", path, vertex_count)
                               : std::vector<Vec3f>{});
  }
  return out;
}

}  // namespace fb::gltf
