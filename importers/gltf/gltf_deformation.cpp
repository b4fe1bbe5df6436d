#include "importers/gltf/gltf_deformation.h"

#include <tiny_gltf.h>

#include <cmath>
#include <limits>

#include "core/util/error.h"
#include "importers/gltf/gltf_accessors.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {
namespace {

constexpr const char* kDeformationExtension = "FILMBACK_deformation";

// The accessor indices of `key` (one per time, or none when absent and `optional`), each
// accessor's count checked against the vertex count before anything is read.
std::vector<long> shape_accessors(const tinygltf::Model& model, const Fields& fields,
                                  const char* key, size_t times, size_t vertex_count,
                                  bool optional) {
  if (!fields.has(key)) {
    if (optional) return {};
    fields.fail(key, "missing; expected one accessor of positions per time");
  }
  const std::vector<long> out = *fields.indices(key, times, model.accessors.size());
  if (out.size() != times)
    fields.fail(key, std::to_string(out.size()) + " accessors for " + std::to_string(times) +
                         " times; expected one per time");
  for (size_t k = 0; k < out.size(); ++k) {
    const std::string where = index_path(key, k);
    if (out[k] < 0) fields.fail(where.c_str(), "no accessor; expected one");
    const size_t count = model.accessors[size_t(out[k])].count;
    if (count != vertex_count)
      fields.fail(where.c_str(), "accessor of " + std::to_string(count) +
                                     " values; expected one per vertex of the primitive (" +
                                     std::to_string(vertex_count) + ")");
  }
  return out;
}

}  // namespace

std::optional<NodeDeformation> read_node_deformation(const tinygltf::Node& node,
                                                     const std::string& node_path,
                                                     size_t primitive_count,
                                                     const std::string& file) {
  const auto ext = node.extensions.find(kDeformationExtension);
  if (ext == node.extensions.end()) return std::nullopt;
  NodeDeformation out;
  out.path = node_path + ".extensions." + kDeformationExtension;
  const Fields fields(ext->second, out.path, file);
  const double big = std::numeric_limits<double>::max();
  const auto times = fields.numbers("times_s", kMaxEvaluatedShapes, -big, big);
  if (!times || times->empty())
    fields.fail("times_s", "missing or empty; expected 1 to " +
                               std::to_string(kMaxEvaluatedShapes) + " times in seconds");
  for (size_t k = 1; k < times->size(); ++k)
    if (!((*times)[k] > (*times)[k - 1]))
      fields.fail("times_s", "time " + std::to_string(k) + " does not follow the one before it; " +
                                 "expected increasing times");
  out.times_s = *times;
  out.world_space = fields.flag("world_space").value_or(false);
  if (fields.type("primitives") != Fields::Type::kArray)
    fields.fail("primitives", "missing; expected one object per primitive of the node's mesh");
  out.primitives = &ext->second.Get("primitives");
  if (out.primitives->ArrayLen() != primitive_count)
    fields.fail("primitives", std::to_string(out.primitives->ArrayLen()) + " entries for " +
                                  std::to_string(primitive_count) +
                                  " primitives; expected one per primitive of the node's mesh");
  return out;
}

EvaluatedShapes read_evaluated_shapes(const tinygltf::Model& model, const NodeDeformation& node,
                                      size_t p, size_t vertex_count, const std::string& file) {
  const Fields fields(node.primitives->Get(int(p)), node.path + "." + index_path("primitives", p),
                      file);
  const size_t times = node.times_s.size();
  if (double(vertex_count) * double(times) > double(kMaxEvaluatedVertexSteps))
    fields.fail("positions", std::to_string(times) + " shapes of " + std::to_string(vertex_count) +
                                 " vertices; at most " + std::to_string(kMaxEvaluatedVertexSteps) +
                                 " positions are read");
  const std::vector<long> positions =
      shape_accessors(model, fields, "positions", times, vertex_count, false);
  const std::vector<long> normals =
      shape_accessors(model, fields, "normals", times, vertex_count, true);
  const AccessorContext ctx{model, file};
  EvaluatedShapes out;
  out.times_s = node.times_s;
  out.shapes.resize(times);
  for (size_t k = 0; k < times; ++k) {
    out.shapes[k].positions =
        read_vec3(ctx, int(positions[k]), fields.path() + "." + index_path("positions", k));
    if (normals.empty()) continue;
    const std::string where = fields.path() + "." + index_path("normals", k);
    out.shapes[k].normals = read_vec3(ctx, int(normals[k]), where);
    for (size_t v = 0; v < vertex_count; ++v)
      if (!(length(Vec3d(out.shapes[k].normals[v])) > 0))
        throw_input(file, where, "normal " + std::to_string(v) + " has zero length");
  }
  return out;
}

}  // namespace fb::gltf
