#include "importers/gltf/gltf_skin.h"

#include <tiny_gltf.h>

#include <array>
#include <cmath>

#include "core/util/error.h"
#include "importers/gltf/gltf_accessors.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {
namespace {

// A vertex's weights may miss one by this much before the file is told they were normalised:
// a little more than WEIGHTS_n stored as normalized unsigned bytes can miss by (4 × 1/510).
constexpr double kSkinWeightSumTolerance = 1e-2;

class SkinReader {
 public:
  SkinReader(const tinygltf::Model& model, const SkinSource& source,
             const std::vector<uint32_t>& scene_node, const std::string& file,
             Diagnostics& diagnostics)
      : model_(model),
        source_(source),
        scene_node_(scene_node),
        file_(file),
        diagnostics_(diagnostics),
        ctx_{model, file} {}

  SkinBinding run() {
    if (source_.skin < 0 || size_t(source_.skin) >= model_.skins.size())
      throw_input(file_, source_.skin_ref,
                  out_of_range("skin", source_.skin, model_.skins.size(), "skins"));
    const tinygltf::Skin& skin = model_.skins[size_t(source_.skin)];
    const std::string path = index_path("skins", size_t(source_.skin));
    SkinBinding out;
    read_joints(skin, path, out);
    read_inverse_binds(skin, path, out);
    read_influences(out);
    return out;
  }

 private:
  void read_joints(const tinygltf::Skin& skin, const std::string& path, SkinBinding& out) {
    if (skin.joints.empty())
      throw_input(file_, path + ".joints", "no joints; expected at least one");
    // glTF's schema asks for unique joints: that also bounds them by the node count.
    std::vector<bool> seen(model_.nodes.size(), false);
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const int node = skin.joints[j];
      const std::string jpath = path + "." + index_path("joints", j);
      if (node < 0 || size_t(node) >= model_.nodes.size())
        throw_input(file_, jpath, out_of_range("node", node, model_.nodes.size(), "nodes"));
      if (seen[size_t(node)])
        throw_input(file_, jpath,
                    index_path("nodes", size_t(node)) +
                        " is a joint of this skin already; expected each joint once");
      seen[size_t(node)] = true;
      if (scene_node_[size_t(node)] == kNoNode)
        throw_input(file_, jpath,
                    index_path("nodes", size_t(node)) +
                        " is not in the rendered scene; a joint must be, to place the skin");
      out.joint_nodes.push_back(scene_node_[size_t(node)]);
    }
  }

  // glTF stores each as a column-major MAT4; absent, every one is the identity.
  void read_inverse_binds(const tinygltf::Skin& skin, const std::string& path, SkinBinding& out) {
    if (skin.inverseBindMatrices < 0) {
      out.inverse_binds.assign(out.joint_nodes.size(), Transform());
      return;
    }
    const std::string where = path + ".inverseBindMatrices";
    const std::vector<double> m =
        read_animation_values(ctx_, skin.inverseBindMatrices, where, TINYGLTF_TYPE_MAT4, false);
    if (m.size() / 16 < out.joint_nodes.size())
      throw_input(file_, where,
                  std::to_string(m.size() / 16) + " matrices for " +
                      std::to_string(out.joint_nodes.size()) + " joints; expected one per joint");
    for (size_t j = 0; j < out.joint_nodes.size(); ++j) {
      std::array<double, 16> columns;
      std::copy_n(&m[16 * j], 16, columns.begin());
      out.inverse_binds.push_back(Transform::from_columns(columns));
    }
  }

  // Every JOINTS_n / WEIGHTS_n pair from n = 0 up, four influences per vertex each.
  void read_influences(SkinBinding& out) {
    const auto& attributes = source_.primitive->attributes;
    const std::string apath = source_.primitive_path + ".attributes";
    size_t sets = 0;
    while (attributes.count("JOINTS_" + std::to_string(sets))) {
      if (++sets > kMaxSkinAttributeSets)
        throw_input(file_, apath + ".JOINTS_" + std::to_string(sets - 1),
                    "more than " + std::to_string(kMaxSkinAttributeSets) +
                        " JOINTS_n sets; expected at most that many");
    }
    if (sets == 0)
      throw_input(file_, apath, "the mesh is skinned but its primitive has no JOINTS_0");
    const size_t n = source_.vertex_count;
    out.influences_per_vertex = uint32_t(4 * sets);
    out.joints.resize(n * 4 * sets);
    out.weights.resize(n * 4 * sets);
    for (size_t s = 0; s < sets; ++s) {
      const std::string joints_path = apath + ".JOINTS_" + std::to_string(s);
      const std::string weights_name = "WEIGHTS_" + std::to_string(s);
      const auto weights = attributes.find(weights_name);
      if (weights == attributes.end())
        throw_input(file_, apath, "JOINTS_" + std::to_string(s) + " without " + weights_name);
      const std::string weights_path = apath + "." + weights_name;
      const std::vector<uint32_t> j =
          read_joint_indices(ctx_, attributes.at("JOINTS_" + std::to_string(s)), joints_path);
      const std::vector<double> w =
          read_animation_values(ctx_, weights->second, weights_path, TINYGLTF_TYPE_VEC4, true);
      check_count(j.size() / 4, joints_path);
      check_count(w.size() / 4, weights_path);
      for (size_t v = 0; v < n; ++v)
        for (size_t c = 0; c < 4; ++c) {
          const size_t from = v * 4 + c, to = v * out.influences_per_vertex + s * 4 + c;
          if (j[from] >= out.joint_nodes.size())
            throw_input(file_, joints_path,
                        "vertex " + std::to_string(v) + " names joint " + std::to_string(j[from]) +
                            ", but the skin has " + std::to_string(out.joint_nodes.size()) +
                            " joints");
          if (w[from] < 0)
            throw_input(file_, weights_path,
                        "vertex " + std::to_string(v) + " has the negative weight " +
                            number_text(w[from]) + "; expected weights in [0, 1]");
          out.joints[to] = j[from];
          out.weights[to] = float(w[from]);
        }
    }
    normalize_weights(out, apath + ".WEIGHTS_0");
  }

  void check_count(size_t count, const std::string& where) {
    if (count != source_.vertex_count)
      throw_input(file_, where,
                  std::to_string(count) + " elements for " + std::to_string(source_.vertex_count) +
                      " positions");
  }

  // glTF asks for weights that sum to one; a file whose do not is rendered as if they did.
  void normalize_weights(SkinBinding& out, const std::string& where) {
    const size_t k = out.influences_per_vertex;
    size_t off = 0;
    for (size_t v = 0; v < source_.vertex_count; ++v) {
      float* w = &out.weights[v * k];
      double sum = 0;
      for (size_t c = 0; c < k; ++c)
        sum += w[c];
      if (!(sum > 0))
        throw_input(
            file_, where,
            "vertex " + std::to_string(v) + "'s weights are all zero; expected them to sum to one");
      if (std::abs(sum - 1) > kSkinWeightSumTolerance) ++off;
      if (sum != 1)
        for (size_t c = 0; c < k; ++c)
          w[c] = float(w[c] / sum);
    }
    if (off > 0)
      diagnostics_.warn(located(
          file_, where, std::to_string(off) + " vertices' weights do not sum to one; normalised"));
  }

  const tinygltf::Model& model_;
  const SkinSource& source_;
  const std::vector<uint32_t>& scene_node_;
  const std::string& file_;
  Diagnostics& diagnostics_;
  AccessorContext ctx_;
};

}  // namespace

SkinBinding read_skin_binding(const tinygltf::Model& model, const SkinSource& source,
                              const std::vector<uint32_t>& scene_node, const std::string& file,
                              Diagnostics& diagnostics) {
  return SkinReader(model, source, scene_node, file, diagnostics).run();
}

}  // namespace fb::gltf
