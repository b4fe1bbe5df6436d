#include "importers/gltf/gltf_animation.h"

#include <tiny_gltf.h>

#include <cmath>
#include <map>

#include "core/util/error.h"
#include "importers/gltf/gltf_accessors.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {
namespace {

class AnimationReader {
 public:
  AnimationReader(const tinygltf::Model& model, const std::string& file,
                  const std::vector<uint32_t>& scene_node, NodeHierarchy& hierarchy,
                  std::map<size_t, AnimationCurve>& morph_weights, Diagnostics& diagnostics)
      : model_(model),
        file_(file),
        scene_node_(scene_node),
        hierarchy_(hierarchy),
        morph_weights_(morph_weights),
        diagnostics_(diagnostics) {}

  void run() {
    for (size_t a = 0; a < model_.animations.size(); ++a) {
      const tinygltf::Animation& animation = model_.animations[a];
      const std::string apath = index_path("animations", a);
      for (size_t c = 0; c < animation.channels.size(); ++c)
        read_channel(animation, apath, c);
    }
  }

 private:
  void read_channel(const tinygltf::Animation& animation, const std::string& apath, size_t c) {
    const tinygltf::AnimationChannel& channel = animation.channels[c];
    const std::string cpath = apath + "." + index_path("channels", c);
    if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
      throw_input(file_, cpath + ".sampler",
                  "sampler index " + std::to_string(channel.sampler) +
                      " is out of range (the animation has " +
                      std::to_string(animation.samplers.size()) + " samplers)");
    static const std::map<std::string, TrsPath> kPaths = {{"translation", TrsPath::kTranslation},
                                                          {"rotation", TrsPath::kRotation},
                                                          {"scale", TrsPath::kScale},
                                                          {"weights", TrsPath::kWeights}};
    const auto path = kPaths.find(channel.target_path);
    if (path == kPaths.end())
      throw_input(file_, cpath + ".target.path",
                  "'" + channel.target_path +
                      "' is not an animated property (expected translation, rotation, scale or "
                      "weights)");
    if (channel.target_node < 0) {
      diagnostics_.warn(
          located(file_, cpath + ".target", "no target node (an extension's target?); ignored"));
      return;
    }
    const size_t target = size_t(channel.target_node);
    if (target >= model_.nodes.size())
      throw_input(file_, cpath + ".target.node",
                  "node index " + std::to_string(target) + " is out of range (the file has " +
                      std::to_string(model_.nodes.size()) + " nodes)");
    if (model_.nodes[target].matrix.size() == 16)
      throw_input(file_, cpath + ".target.node",
                  index_path("nodes", target) +
                      " has a matrix; glTF lets animation target only nodes with "
                      "translation, rotation and scale");
    const uint32_t node = scene_node_[target];
    if (node == kNoNode) return;  // not in the rendered scene: moves nothing
    if (path->second == TrsPath::kWeights) {
      read_morph_weights(animation, apath, channel, cpath, target);
      return;
    }
    const auto key = std::pair{node, path->second};
    if (const auto first = claimed_.find(key); first != claimed_.end()) {
      diagnostics_.warn(located(file_, cpath,
                                index_path("nodes", target) + "." + channel.target_path +
                                    " is already animated by " + first->second + "; ignored"));
      return;
    }
    claimed_.emplace(key, cpath);
    hierarchy_.curves.push_back(read_curve(
        animation.samplers[size_t(channel.sampler)],
        apath + "." + index_path("samplers", size_t(channel.sampler)), node, path->second));
  }

  // A `weights` channel: one value per morph target of the node's mesh (glTF 2.0 §3.11).
  void read_morph_weights(const tinygltf::Animation& animation, const std::string& apath,
                          const tinygltf::AnimationChannel& channel, const std::string& cpath,
                          size_t target) {
    const tinygltf::Node& node = model_.nodes[target];
    const size_t targets = node.mesh >= 0 && size_t(node.mesh) < model_.meshes.size() &&
                                   !model_.meshes[size_t(node.mesh)].primitives.empty()
                               ? model_.meshes[size_t(node.mesh)].primitives[0].targets.size()
                               : 0;
    if (targets == 0) {
      diagnostics_.warn(located(
          file_, cpath + ".target.node",
          index_path("nodes", target) + " has no morph targets for its weights to move; ignored"));
      return;
    }
    if (morph_weights_.count(target)) {
      diagnostics_.warn(located(
          file_, cpath, index_path("nodes", target) + ".weights is already animated; ignored"));
      return;
    }
    morph_weights_.emplace(
        target, read_curve(animation.samplers[size_t(channel.sampler)],
                           apath + "." + index_path("samplers", size_t(channel.sampler)), kNoNode,
                           TrsPath::kWeights, uint32_t(targets)));
  }

  AnimationCurve read_curve(const tinygltf::AnimationSampler& sampler, const std::string& spath,
                            uint32_t node, TrsPath path, uint32_t weight_count = 0) {
    AnimationCurve curve;
    curve.node = node;
    curve.path = path;
    curve.weight_count = weight_count;
    if (sampler.interpolation == "LINEAR")
      curve.interpolation = Interpolation::kLinear;
    else if (sampler.interpolation == "STEP")
      curve.interpolation = Interpolation::kStep;
    else if (sampler.interpolation == "CUBICSPLINE")
      curve.interpolation = Interpolation::kCubicSpline;
    else
      throw_input(file_, spath + ".interpolation",
                  "'" + sampler.interpolation + "', expected LINEAR, STEP or CUBICSPLINE");
    const AccessorContext ctx{model_, file_};
    const std::string input = spath + ".input (accessors[" + std::to_string(sampler.input) + "])";
    curve.times_s =
        read_animation_values(ctx, sampler.input, spath + ".input", TINYGLTF_TYPE_SCALAR, false);
    const bool cubic = curve.interpolation == Interpolation::kCubicSpline;
    const size_t keys = curve.times_s.size();
    if (keys < (cubic ? 2u : 1u))
      throw_input(file_, input,
                  std::to_string(keys) + " keys, expected at least " + (cubic ? "two" : "one"));
    // glTF asks for time[0] >= 0 too; Blender 3.4 writes keys before frame 0 at negative times,
    // which evaluate just as well, so only order and finiteness are required.
    for (size_t k = 1; k < keys; ++k)
      if (!(curve.times_s[k] > curve.times_s[k - 1]))
        throw_input(file_, input,
                    "key " + std::to_string(k) + " at " + number_text(curve.times_s[k]) +
                        " s does not follow key " + std::to_string(k - 1) + " at " +
                        number_text(curve.times_s[k - 1]) +
                        " s; expected strictly increasing times");
    const bool rotation = path == TrsPath::kRotation, weights = path == TrsPath::kWeights;
    const std::string output =
        spath + ".output (accessors[" + std::to_string(sampler.output) + "])";
    // Rotations and weights may be normalized integers; weights are SCALARs, targets per key.
    curve.values = read_animation_values(ctx, sampler.output, spath + ".output",
                                         rotation  ? TINYGLTF_TYPE_VEC4
                                         : weights ? TINYGLTF_TYPE_SCALAR
                                                   : TINYGLTF_TYPE_VEC3,
                                         rotation || weights);
    const size_t expected = keys * (cubic ? 3 : 1);
    const size_t w = curve.width();
    if (curve.values.size() != expected * w)
      throw_input(file_, output,
                  std::to_string(curve.values.size() / w) + " values for " + std::to_string(keys) +
                      " keys, expected " + std::to_string(expected) +
                      (cubic ? " (in-tangent, value, out-tangent per key)" : ""));
    if (rotation) normalize_rotations(curve, output);
    return curve;
  }

  // Key values are unit quaternions in glTF; quantised ones are only nearly so. Tangents stay.
  void normalize_rotations(AnimationCurve& curve, const std::string& output) {
    const bool cubic = curve.interpolation == Interpolation::kCubicSpline;
    for (size_t k = 0; k < curve.times_s.size(); ++k) {
      double* q = &curve.values[(cubic ? 3 * k + 1 : k) * 4];
      const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      if (!(n > 1e-6) || !std::isfinite(n))
        throw_input(file_, output,
                    "key " + std::to_string(k) + " is not a rotation (quaternion of length " +
                        number_text(n) + ", expected 1)");
      for (int i = 0; i < 4; ++i)
        q[i] /= n;
    }
  }

  const tinygltf::Model& model_;
  const std::string& file_;
  const std::vector<uint32_t>& scene_node_;
  NodeHierarchy& hierarchy_;
  std::map<size_t, AnimationCurve>& morph_weights_;
  Diagnostics& diagnostics_;
  std::map<std::pair<uint32_t, TrsPath>, std::string> claimed_;  // the channel that moves each
};

}  // namespace

void read_animations(const tinygltf::Model& model, const std::string& file,
                     const std::vector<uint32_t>& scene_node, NodeHierarchy& hierarchy,
                     std::map<size_t, AnimationCurve>& morph_weights, Diagnostics& diagnostics) {
  AnimationReader(model, file, scene_node, hierarchy, morph_weights, diagnostics).run();
}

}  // namespace fb::gltf
