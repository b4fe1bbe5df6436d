#include "importers/gltf/gltf_subdivision.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "core/util/error.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {
namespace {

// Far OpenSubdiv's own limits (Vtr::VALENCE_LIMIT, 16-bit local indices) bound the face size; the
// counts bound what an untrusted file can make us allocate before the refinement's own cap.
constexpr size_t kMaxFaceSize = 0xffff;
constexpr size_t kMaxCageVertices = size_t(1) << 24;
constexpr size_t kMaxFaceVertices = size_t(1) << 26;
constexpr double kMaxLevel = 11;  // Blender's hard maximum for levels_render
constexpr double kMaxQuality = 10;

// The subdivision object's members: gltf::Fields for scalars, plus the cage's arrays.
class Reader {
 public:
  Reader(const tinygltf::Value& object, const std::string& path, const std::string& file)
      : fields_(object, path, file), object_(object), path_(path), file_(file) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw_input(file_, path_ + (where.empty() ? "" : "." + where), what);
  }

  std::optional<double> whole(const char* key, double lo, double hi) const {
    return fields_.whole(key, lo, hi);
  }
  std::optional<bool> flag(const char* key) const { return fields_.flag(key); }

  // One of `names` (as Blender spells them); returns its position in the list.
  std::optional<size_t> choice(const char* key, std::initializer_list<const char*> names) const {
    const std::optional<std::string> word = fields_.word(key);
    if (!word) return std::nullopt;
    std::string expected;
    size_t i = 0;
    for (const char* name : names) {
      if (*word == name) return i;
      expected += (i++ ? " or " : "") + std::string(name);
    }
    fail(key, "expected " + expected);
  }

  // The array under `key`, its length a multiple of `stride` and at most `max` elements.
  const tinygltf::Value::Array* array(const char* key, size_t stride, size_t max,
                                      bool required) const {
    if (!object_.Has(key)) {
      if (required) fail("", std::string("expected an array '") + key + "'");
      return nullptr;
    }
    const tinygltf::Value& v = object_.Get(key);
    if (!v.IsArray()) fail(key, "expected an array");
    const auto& a = v.Get<tinygltf::Value::Array>();
    if (a.size() % stride != 0 || a.size() > max)
      fail(key, std::to_string(a.size()) + " elements, expected a multiple of " +
                    std::to_string(stride) + " up to " + std::to_string(max));
    return &a;
  }

  static double element(const tinygltf::Value::Array& a, size_t i) {
    return a[i].IsNumber() ? a[i].GetNumberAsDouble() : NAN;
  }

  // A whole number in [lo, hi] at a[i].
  uint32_t index(const tinygltf::Value::Array& a, const char* key, size_t i, double lo, double hi,
                 const char* what) const {
    const double x = element(a, i);
    if (!(x >= lo && x <= hi && x == std::floor(x)))
      fail(std::string(key) + "[" + std::to_string(i) + "]",
           "expected " + std::string(what) + " from " + number_text(lo) + " to " + number_text(hi));
    return uint32_t(x);
  }

  float weight(const tinygltf::Value::Array& a, const char* key, size_t i) const {
    const double x = element(a, i);
    if (!(x >= 0 && x <= 1))
      fail(std::string(key) + "[" + std::to_string(i) + "]", "expected a crease weight in [0, 1]");
    return float(x);
  }

 private:
  Fields fields_;
  const tinygltf::Value& object_;
  const std::string& path_;
  const std::string& file_;
};

uint64_t edge_key(uint32_t a, uint32_t b) {
  return (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

void read_settings(const Reader& r, SubdivisionSettings& s) {
  if (auto v = r.whole("levels_render", 0, kMaxLevel)) s.levels_render = uint32_t(*v);
  if (auto v = r.whole("quality", 1, kMaxQuality)) s.quality = uint32_t(*v);
  if (auto v = r.choice("scheme", {"CATMULL_CLARK", "SIMPLE"}))
    s.scheme = SubdivisionSettings::Scheme(*v);
  if (auto v = r.choice("boundary_smooth", {"ALL", "PRESERVE_CORNERS"}))
    s.boundary_smooth = SubdivisionSettings::Boundary(*v);
  if (auto v = r.flag("use_creases")) s.use_creases = *v;
  if (auto v = r.flag("use_limit_surface")) s.use_limit_surface = *v;
  // uv_smooth concerns texture coordinates, which the refinement does not carry yet.
  r.choice("uv_smooth",
           {"NONE", "PRESERVE_CORNERS", "PRESERVE_CORNERS_AND_JUNCTIONS",
            "PRESERVE_CORNERS_JUNCTIONS_AND_CONCAVE", "PRESERVE_BOUNDARIES", "SMOOTH_ALL"});
}

}  // namespace

SubdivisionSurface read_subdivision(const tinygltf::Value& subdivision, const std::string& path,
                                    const std::string& file) {
  if (!subdivision.IsObject()) throw_input(file, path, "expected an object");
  const Reader r(subdivision, path, file);
  SubdivisionSurface out;
  read_settings(r, out.settings);

  const auto& positions = *r.array("cage_positions", 3, 3 * kMaxCageVertices, true);
  out.cage_positions.reserve(positions.size() / 3);
  for (size_t i = 0; i < positions.size(); i += 3) {
    float xyz[3];
    for (size_t k = 0; k < 3; ++k) {
      const double x = r.element(positions, i + k);
      if (!(std::abs(x) <= 3.4e38))  // finite as a float
        r.fail("cage_positions[" + std::to_string(i + k) + "]", "expected a finite number");
      xyz[k] = float(x);
    }
    out.cage_positions.push_back({xyz[0], xyz[1], xyz[2]});
  }
  const double last_vertex = double(out.cage_positions.size()) - 1;
  if (out.cage_positions.empty()) r.fail("cage_positions", "expected at least one vertex");

  const auto& sizes = *r.array("cage_face_sizes", 1, kMaxFaceVertices / 3, true);
  const auto& vertices = *r.array("cage_face_vertices", 1, kMaxFaceVertices, true);
  out.cage_face_sizes.resize(sizes.size());
  size_t total = 0;
  for (size_t f = 0; f < sizes.size(); ++f)
    total += (out.cage_face_sizes[f] =
                  r.index(sizes, "cage_face_sizes", f, 3, kMaxFaceSize, "a face size"));
  if (sizes.empty()) r.fail("cage_face_sizes", "expected at least one face");
  if (total != vertices.size())
    r.fail("cage_face_vertices", std::to_string(vertices.size()) + " vertex indices, expected " +
                                     std::to_string(total) + " (the sum of cage_face_sizes)");
  out.cage_face_vertices.resize(total);
  std::unordered_set<uint64_t> edges;
  std::vector<uint32_t> sorted;
  for (size_t f = 0, first = 0; f < sizes.size(); first += out.cage_face_sizes[f++]) {
    const size_t n = out.cage_face_sizes[f];
    for (size_t k = 0; k < n; ++k)
      out.cage_face_vertices[first + k] =
          r.index(vertices, "cage_face_vertices", first + k, 0, last_vertex, "a vertex index");
    for (size_t k = 0; k < n; ++k)
      edges.insert(
          edge_key(out.cage_face_vertices[first + k], out.cage_face_vertices[first + (k + 1) % n]));
    // A face through one vertex twice has a zero-length edge OpenSubdiv cannot refine.
    sorted.assign(out.cage_face_vertices.begin() + ptrdiff_t(first),
                  out.cage_face_vertices.begin() + ptrdiff_t(first + n));
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      r.fail("cage_face_sizes[" + std::to_string(f) + "]",
             "the face uses a vertex twice; expected distinct vertices");
  }

  if (const auto* creases = r.array("edge_creases", 3, 3 * edges.size(), false))
    for (size_t i = 0; i < creases->size(); i += 3) {
      EdgeCrease c;
      c.v0 = r.index(*creases, "edge_creases", i, 0, last_vertex, "a vertex index");
      c.v1 = r.index(*creases, "edge_creases", i + 1, 0, last_vertex, "a vertex index");
      c.weight = r.weight(*creases, "edge_creases", i + 2);
      if (!edges.count(edge_key(c.v0, c.v1)))
        r.fail("edge_creases[" + std::to_string(i) + "]",
               "vertices " + std::to_string(c.v0) + " and " + std::to_string(c.v1) +
                   " are not joined by a cage edge; expected an edge of the cage");
      out.edge_creases.push_back(c);
    }
  if (const auto* creases = r.array("vertex_creases", 2, 2 * out.cage_positions.size(), false))
    for (size_t i = 0; i < creases->size(); i += 2)
      out.vertex_creases.push_back(
          {r.index(*creases, "vertex_creases", i, 0, last_vertex, "a vertex index"),
           r.weight(*creases, "vertex_creases", i + 1)});
  return out;
}

}  // namespace fb::gltf

namespace fb::gltf {

std::optional<SubdivisionSurface> read_node_subdivision(const tinygltf::Model& model,
                                                        const tinygltf::Node& node,
                                                        const std::string& path,
                                                        const Transform& world, uint32_t scene_node,
                                                        const std::string& file) {
  const auto ext = node.extensions.find("FILMBACK_blender");
  if (ext == node.extensions.end() || !ext->second.IsObject() || !ext->second.Has("subdivision"))
    return std::nullopt;
  const std::string sub_path = path + ".extensions.FILMBACK_blender.subdivision";
  if (node.mesh < 0 || size_t(node.mesh) >= model.meshes.size())
    throw_input(file, sub_path, "expected the node to have a mesh (the cage's triangulation)");
  SubdivisionSurface s = read_subdivision(ext->second.Get("subdivision"), sub_path, file);
  const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
  s.name = !node.name.empty() ? node.name : !mesh.name.empty() ? mesh.name : path;
  s.node = node.name.empty() ? path : node.name;
  s.node_index = scene_node;
  s.world_from_object = world;
  s.material = kNoSubdivisionMaterial;
  if (!mesh.primitives.empty() && mesh.primitives[0].material >= 0) {
    const int m = mesh.primitives[0].material;
    if (size_t(m) >= model.materials.size())
      throw_input(file, "meshes[" + std::to_string(node.mesh) + "].primitives[0].material",
                  "material index " + std::to_string(m) + " is out of range (the file has " +
                      std::to_string(model.materials.size()) + " materials)");
    s.material = uint32_t(m);
  }
  return s;
}

}  // namespace fb::gltf
