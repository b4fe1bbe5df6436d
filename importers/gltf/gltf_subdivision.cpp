#include "importers/gltf/gltf_subdivision.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "core/util/error.h"
#include "importers/gltf/gltf_blender_material.h"
#include "importers/gltf/gltf_json.h"
#include "importers/gltf/gltf_materials.h"

namespace fb::gltf {
namespace {

// Far OpenSubdiv's own limits (Vtr::VALENCE_LIMIT, 16-bit local indices) bound the face size; the
// counts bound what an untrusted file can make us allocate before the refinement's own cap.
constexpr size_t kMaxFaceSize = 0xffff;
constexpr size_t kMaxCageVertices = size_t(1) << 24;
constexpr size_t kMaxFaceVertices = size_t(1) << 26;
constexpr double kMaxLevel = 11;  // Blender's hard maximum for levels_render
constexpr double kMaxQuality = 10;
constexpr size_t kMaxUvMaps = 8;  // Blender's MAX_MTFACE

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
  if (auto v = r.choice("uv_smooth", {"NONE", "PRESERVE_CORNERS", "PRESERVE_CORNERS_AND_JUNCTIONS",
                                      "PRESERVE_CORNERS_JUNCTIONS_AND_CONCAVE",
                                      "PRESERVE_BOUNDARIES", "SMOOTH_ALL"}))
    s.uv_smooth = SubdivisionSettings::UvSmooth(*v);
}

// uv_maps: [{"name": ..., "uvs": [u, v, ...]}, ...], a texture coordinate per face corner.
void read_uv_maps(const tinygltf::Value& subdivision, const std::string& path,
                  const std::string& file, size_t corners, SubdivisionSurface& out) {
  if (!subdivision.Has("uv_maps")) return;
  const tinygltf::Value& maps = subdivision.Get("uv_maps");
  if (!maps.IsArray() || maps.ArrayLen() > kMaxUvMaps)
    throw_input(file, path + ".uv_maps",
                "expected an array of at most " + std::to_string(kMaxUvMaps) + " UV maps");
  for (size_t m = 0; m < maps.ArrayLen(); ++m) {
    const std::string at = path + "." + index_path("uv_maps", m);
    const tinygltf::Value& map = maps.Get(int(m));
    if (!map.IsObject()) throw_input(file, at, "expected an object");
    const Reader r(map, at, file);
    SubdivisionUvMap uv_map;
    const std::optional<std::string> name = Fields(map, at, file).word("name");
    if (!name) r.fail("", "expected a string 'name'");
    uv_map.name = *name;
    const auto& uvs = *r.array("uvs", 2, 2 * kMaxFaceVertices, true);
    if (uvs.size() != 2 * corners)
      r.fail("uvs", std::to_string(uvs.size()) + " elements, expected " +
                        std::to_string(2 * corners) + " (u, v for each of the cage's corners)");
    uv_map.corner_uvs.resize(corners);
    for (size_t i = 0; i < uvs.size(); ++i) {
      const double x = r.element(uvs, i);
      if (!(std::abs(x) <= 3.4e38))  // finite as a float
        r.fail("uvs[" + std::to_string(i) + "]", "expected a finite number");
      (i % 2 ? uv_map.corner_uvs[i / 2].y : uv_map.corner_uvs[i / 2].x) = float(x);
    }
    out.uv_maps.push_back(std::move(uv_map));
  }
}

}  // namespace

SubdivisionSurface read_subdivision(const tinygltf::Value& subdivision, const std::string& path,
                                    const std::string& file, size_t primitive_count) {
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
  read_uv_maps(subdivision, path, file, total, out);
  if (const auto* faces = r.array("face_primitives", 1, kMaxFaceVertices, false)) {
    if (faces->size() != sizes.size())
      r.fail("face_primitives", std::to_string(faces->size()) + " elements, expected " +
                                    std::to_string(sizes.size()) + " (one per cage face)");
    out.face_parts.resize(faces->size());
    for (size_t f = 0; f < faces->size(); ++f)
      out.face_parts[f] = r.index(*faces, "face_primitives", f, 0, double(primitive_count) - 1,
                                  "a primitive of the node's mesh");
  }
  return out;
}

}  // namespace fb::gltf

namespace fb::gltf {

namespace {

// The glTF material index of each of the mesh's primitives (kNoSubdivisionMaterial for none).
std::vector<uint32_t> primitive_materials(const tinygltf::Model& model, int mesh_index,
                                          const std::string& file) {
  const tinygltf::Mesh& mesh = model.meshes[size_t(mesh_index)];
  std::vector<uint32_t> out;
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const int m = mesh.primitives[p].material;
    if (m >= 0 && size_t(m) >= model.materials.size())
      throw_input(file,
                  index_path("meshes", size_t(mesh_index)) + "." + index_path("primitives", p) +
                      ".material",
                  out_of_range("material", m, model.materials.size(), "materials"));
    out.push_back(m < 0 ? kNoSubdivisionMaterial : uint32_t(m));
  }
  return out;
}

// One part per material the faces wear (face_parts holds primitive indices until then).
void make_parts(const std::vector<uint32_t>& materials, SubdivisionSurface& s) {
  s.parts.clear();
  std::vector<uint32_t> part_of_material;  // parallel to the parts' materials
  const auto part = [&](uint32_t material) {
    const auto it = std::find(part_of_material.begin(), part_of_material.end(), material);
    if (it != part_of_material.end()) return uint32_t(it - part_of_material.begin());
    part_of_material.push_back(material);
    s.parts.push_back({material});
    return uint32_t(s.parts.size() - 1);
  };
  for (uint32_t& p : s.face_parts)
    p = part(materials[p]);
  if (s.face_parts.empty()) part(materials.empty() ? kNoSubdivisionMaterial : materials[0]);
  if (s.parts.size() == 1) s.face_parts.clear();
}

// Each part's texture-coordinate slots from the cage's UV maps, found as a triangle primitive's
// TEXCOORD_n are (gltf_materials.h, plan_texcoords: map n stands for TEXCOORD_n); then only the
// maps some part reads are kept.
void plan_uv_maps(const std::vector<Material>& materials, const Fields& mesh_extension,
                  const std::string& path, Diagnostics& diagnostics, SubdivisionSurface& s) {
  MeshUvMaps maps = read_mesh_uv_maps(mesh_extension);
  maps.names.clear();
  for (const SubdivisionUvMap& map : s.uv_maps)
    maps.names.push_back(map.name);
  if (maps.active_render.empty() && !maps.names.empty()) maps.active_render = maps.names[0];
  std::vector<uint32_t> kept(s.uv_maps.size(), kNoUvMap);
  uint32_t kept_count = 0;
  for (SubdivisionPart& part : s.parts) {
    if (part.material == kNoSubdivisionMaterial) continue;  // the default material reads none
    const Material& material = materials[part.material];
    const TexcoordPlan plan =
        plan_texcoords(material, maps, mesh_extension.file(), path, diagnostics);
    for (uint32_t slot = 0; slot < VertexTextureData::kSets; ++slot) {
      if (!plan.slots[slot]) continue;
      const uint32_t n = *plan.slots[slot];
      if (n >= s.uv_maps.size()) {
        if (plan.required[slot])
          throw_input(mesh_extension.file(), path + ".uv_maps",
                      "material '" + material.name + "' reads TEXCOORD_" + std::to_string(n) +
                          ", and the cage has " + std::to_string(s.uv_maps.size()) +
                          " UV maps; expected UV map " + std::to_string(n));
        if (material.shader_graph)
          diagnostics.warn(located(mesh_extension.file(), path,
                                   "no UV map " + std::to_string(n) + " for '" +
                                       material.shader_graph->uv_maps[slot] +
                                       "' in the cage: its textures read the point (0, 0)"));
        continue;
      }
      if (kept[n] == kNoUvMap) kept[n] = kept_count++;
      part.slot_uv_maps[slot] = kept[n];
    }
    if (plan.tangent_slot) part.tangent_slot = *plan.tangent_slot;
  }
  std::vector<SubdivisionUvMap> used(kept_count);
  for (size_t n = 0; n < kept.size(); ++n)
    if (kept[n] != kNoUvMap) used[kept[n]] = std::move(s.uv_maps[n]);
  s.uv_maps = std::move(used);
}

}  // namespace

std::optional<SubdivisionSurface> read_node_subdivision(
    const tinygltf::Model& model, const tinygltf::Node& node, const std::string& path,
    const Transform& world, uint32_t scene_node, const std::vector<Material>& materials,
    const std::string& file, Diagnostics& diagnostics) {
  const auto ext = node.extensions.find("FILMBACK_blender");
  if (ext == node.extensions.end() || !ext->second.IsObject() || !ext->second.Has("subdivision"))
    return std::nullopt;
  const std::string sub_path = path + ".extensions.FILMBACK_blender.subdivision";
  if (node.mesh < 0 || size_t(node.mesh) >= model.meshes.size())
    throw_input(file, sub_path, "expected the node to have a mesh (the cage's triangulation)");
  const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
  SubdivisionSurface s =
      read_subdivision(ext->second.Get("subdivision"), sub_path, file, mesh.primitives.size());
  s.name = !node.name.empty() ? node.name : !mesh.name.empty() ? mesh.name : path;
  s.node = node.name.empty() ? path : node.name;
  s.node_index = scene_node;
  s.world_from_object = world;
  make_parts(primitive_materials(model, node.mesh, file), s);
  static const tinygltf::Value kNone;
  const auto ours = mesh.extensions.find("FILMBACK_blender");
  const Fields mesh_extension(
      ours == mesh.extensions.end() ? kNone : ours->second,
      index_path("meshes", size_t(node.mesh)) + ".extensions.FILMBACK_blender", file);
  plan_uv_maps(materials, mesh_extension, sub_path, diagnostics, s);
  return s;
}

}  // namespace fb::gltf
