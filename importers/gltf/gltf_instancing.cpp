#include "importers/gltf/gltf_instancing.h"

#include <tiny_gltf.h>

#include "core/scene/animation.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_accessors.h"

namespace fb::gltf {

void check_instance_count(size_t existing, size_t more, const std::string& file,
                          const std::string& where) {
  if (more > kMaxInstances - std::min(existing, kMaxInstances))
    throw_input(file, where,
                "the file makes " + std::to_string(existing) + " mesh instances before this and " +
                    std::to_string(more) + " more here; expected at most " +
                    std::to_string(kMaxInstances) + " in all");
}

std::optional<std::vector<Transform>> read_gpu_instances(const tinygltf::Model& model,
                                                         const tinygltf::Node& node,
                                                         const std::string& node_path,
                                                         const std::string& file, size_t existing) {
  const auto extension = node.extensions.find("EXT_mesh_gpu_instancing");
  if (extension == node.extensions.end()) return std::nullopt;
  const std::string path = node_path + ".extensions.EXT_mesh_gpu_instancing.attributes";
  const tinygltf::Value& attributes = extension->second.Get("attributes");
  if (!attributes.IsObject()) throw_input(file, path, "expected an object of accessors");
  // Each attribute's accessor index and declared count, checked before anything is read.
  struct Attribute {
    const char* name;
    int accessor = -1;
  } translation{"TRANSLATION"}, rotation{"ROTATION"}, scale{"SCALE"};
  std::optional<size_t> count;
  for (Attribute* a : {&translation, &rotation, &scale}) {
    if (!attributes.Has(a->name)) continue;
    const std::string where = path + "." + a->name;
    const tinygltf::Value& index = attributes.Get(a->name);
    if (!index.IsInt() || index.Get<int>() < 0 ||
        size_t(index.Get<int>()) >= model.accessors.size())
      throw_input(file, where,
                  "expected an accessor index below " + std::to_string(model.accessors.size()));
    a->accessor = index.Get<int>();
    const size_t n = model.accessors[size_t(a->accessor)].count;
    check_instance_count(existing, n, file, where);
    if (count && *count != n)
      throw_input(file, where,
                  std::to_string(n) + " instances, expected " + std::to_string(*count) +
                      " as the other attributes have");
    count = n;
  }
  if (!count) throw_input(file, path, "expected TRANSLATION, ROTATION or SCALE");
  const AccessorContext ctx{model, file};
  std::vector<Trs> placements(*count);
  if (translation.accessor >= 0) {
    const std::vector<Vec3f> t = read_vec3(ctx, translation.accessor, path + ".TRANSLATION");
    for (size_t i = 0; i < t.size(); ++i)
      placements[i].translation = Vec3d(t[i]);
  }
  if (rotation.accessor >= 0) {
    // Float, or normalized byte or short, as the extension allows.
    const std::vector<double> q =
        read_animation_values(ctx, rotation.accessor, path + ".ROTATION", TINYGLTF_TYPE_VEC4, true);
    for (size_t i = 0; i < placements.size(); ++i)
      placements[i].rotation = {q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]};
  }
  if (scale.accessor >= 0) {
    const std::vector<Vec3f> s = read_vec3(ctx, scale.accessor, path + ".SCALE");
    for (size_t i = 0; i < s.size(); ++i)
      placements[i].scale = Vec3d(s[i]);
  }
  std::vector<Transform> node_from_instance;
  node_from_instance.reserve(placements.size());
  for (size_t i = 0; i < placements.size(); ++i) {
    node_from_instance.push_back(placements[i].matrix());
    if (!node_from_instance.back().is_finite())
      throw_input(file, path,
                  "instance " + std::to_string(i) +
                      "'s transform is not finite (a zero rotation quaternion?)");
  }
  return node_from_instance;
}

}  // namespace fb::gltf
