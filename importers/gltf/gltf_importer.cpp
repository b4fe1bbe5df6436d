#include "importers/gltf/gltf_importer.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include "core/util/error.h"
#include "importers/gltf/gltf_accessors.h"
#include "importers/gltf/gltf_animation.h"
#include "importers/gltf/gltf_camera.h"
#include "importers/gltf/gltf_deformation.h"
#include "importers/gltf/gltf_file.h"
#include "importers/gltf/gltf_instancing.h"
#include "importers/gltf/gltf_json.h"
#include "importers/gltf/gltf_lights.h"
#include "importers/gltf/gltf_materials.h"
#include "importers/gltf/gltf_morph.h"
#include "importers/gltf/gltf_shot.h"
#include "importers/gltf/gltf_skin.h"
#include "importers/gltf/gltf_subdivision.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

using gltf::index_path;
using gltf::out_of_range;

class Importer {
 public:
  Importer(const fs::path& file, Diagnostics& diagnostics)
      : file_(file), name_(file.string()), diagnostics_(diagnostics) {}

  Scene run() {
    load();
    check_extensions();
    scene_.file = file_;
    gltf::read_materials(model_, name_, scene_, diagnostics_);
    // The node hierarchy is kept only when something can move (animation, or joints that place
    // a skinned mesh): a static file costs nothing more.
    keep_nodes_ = !model_.animations.empty() || !model_.skins.empty();
    walk_nodes();
    std::map<size_t, AnimationCurve> morph_weights;
    if (keep_nodes_) {
      gltf::read_animations(model_, name_, scene_node_, scene_.hierarchy, morph_weights,
                            diagnostics_);
      scene_.hierarchy.finish();
    }
    // After the walk: a skin's joints may be met after the mesh they move.
    for (Deformed& d : deformed_) {
      if (d.skin.skin >= 0)
        d.deformation.skin =
            gltf::read_skin_binding(model_, d.skin, scene_node_, name_, diagnostics_);
      if (const auto curve = morph_weights.find(d.node);
          curve != morph_weights.end() && !d.deformation.morph.empty())
        d.deformation.morph.weight_curve = curve->second;
      scene_.deformations.push_back(std::move(d.deformation));
    }
    return std::move(scene_);
  }

 private:
  void warn(const std::string& where, const std::string& what) {
    diagnostics_.warn(located(name_, where, what));
  }

  void load() { gltf::load_model(file_, model_); }

  void check_extensions() {
    // One extension a line: each is read by its own part of the importer.
    static const std::set<std::string> kSupported = {
        "EXT_camera_physical",   "KHR_lights_punctual",    "KHR_materials_emissive_strength",
        "KHR_materials_ior",     "KHR_materials_specular", "KHR_materials_transmission",
        "KHR_texture_transform", "FILMBACK_blender",       "EXT_mesh_gpu_instancing",
        "FILMBACK_povray",       "FILMBACK_deformation",
    };
    for (size_t i = 0; i < model_.extensionsRequired.size(); ++i)
      if (!kSupported.count(model_.extensionsRequired[i]))
        throw_input(name_, index_path("extensionsRequired", i),
                    model_.extensionsRequired[i] + " is required by the file but not supported");
    for (size_t i = 0; i < model_.extensionsUsed.size(); ++i)
      if (!kSupported.count(model_.extensionsUsed[i]))
        warn(index_path("extensionsUsed", i),
             model_.extensionsUsed[i] + " is not supported yet; ignored");
  }

  // FILMBACK_blender's settings when the scene has the extension, else extras of the same names.
  ShotSettings read_shot_settings(const tinygltf::Scene& scene, const std::string& path) {
    if (const auto ours = scene.extensions.find("FILMBACK_blender"); ours != scene.extensions.end())
      return gltf::read_shot_settings(
          gltf::Fields(ours->second, path + ".extensions.FILMBACK_blender", name_));
    return gltf::read_shot_settings(gltf::Fields(scene.extras, path + ".extras", name_));
  }

  uint32_t default_material() {
    if (!default_material_) {
      default_material_ = uint32_t(scene_.materials.size());
      Material m;
      m.name = "default (primitive without material)";
      scene_.materials.push_back(m);
    }
    return *default_material_;
  }

  // The node's rest pose: its matrix, or T·R·S with `trs` set to the parts.
  Transform local_transform(const tinygltf::Node& node, const std::string& path, Trs& trs) {
    Transform t;
    if (node.matrix.size() == 16) {
      std::array<double, 16> m;
      std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
      t = Transform::from_columns(m);
    } else {
      if (node.translation.size() == 3)
        trs.translation = {node.translation[0], node.translation[1], node.translation[2]};
      if (node.rotation.size() == 4)
        trs.rotation = {node.rotation[0], node.rotation[1], node.rotation[2], node.rotation[3]};
      if (node.scale.size() == 3) trs.scale = {node.scale[0], node.scale[1], node.scale[2]};
      t = trs.matrix();
    }
    if (!t.is_finite()) throw_input(name_, path, "the node's transform is not finite");
    return t;
  }

  // Depth-first over the scene's node trees, iteratively: a hostile file cannot overflow the stack.
  // glTF requires the hierarchy to be a set of disjoint trees ("Nodes and Hierarchy"): a node
  // reached twice (a cycle, or two parents) is an error, named at the reference that reached it.
  void walk_nodes() {
    struct Pending {
      int index;
      Transform parent;
      uint32_t parent_node;  // in scene_.hierarchy when keep_nodes_
      std::string from;      // the JSON path of the reference to the node
      uint32_t asset;        // in scene_.assets: the tree's root; kNoAsset for a root
    };
    scene_node_.assign(model_.nodes.size(), kNoNode);
    std::vector<Pending> stack;
    if (!model_.scenes.empty()) {
      const size_t s = model_.defaultScene >= 0 ? size_t(model_.defaultScene) : 0;
      if (s >= model_.scenes.size())
        throw_input(name_, "scene", out_of_range("scene", long(s), model_.scenes.size(), "scenes"));
      scene_.settings = read_shot_settings(model_.scenes[s], index_path("scenes", s));
      gltf::read_world(model_, s, name_, scene_);
      const std::vector<int>& roots = model_.scenes[s].nodes;
      for (size_t r = roots.size(); r-- > 0;)
        stack.push_back({roots[r], Transform(), kNoNode,
                         index_path("scenes", s) + "." + index_path("nodes", r), kNoAsset});
      if (model_.scenes.size() > 1)
        warn("scenes", "the file has " + std::to_string(model_.scenes.size()) +
                           " scenes; rendering scenes[" + std::to_string(s) + "]");
    } else {
      // No scene: every node without a parent is a root.
      std::vector<bool> is_child(model_.nodes.size(), false);
      for (const auto& node : model_.nodes)
        for (int c : node.children)
          if (c >= 0 && size_t(c) < is_child.size()) is_child[size_t(c)] = true;
      for (size_t i = model_.nodes.size(); i-- > 0;)
        if (!is_child[i])
          stack.push_back({int(i), Transform(), kNoNode, index_path("nodes", i), kNoAsset});
    }
    std::vector<bool> visited(model_.nodes.size(), false);
    while (!stack.empty()) {
      const Pending next = std::move(stack.back());
      stack.pop_back();
      if (next.index < 0 || size_t(next.index) >= model_.nodes.size())
        throw_input(name_, next.from,
                    out_of_range("node", next.index, model_.nodes.size(), "nodes"));
      const std::string path = index_path("nodes", size_t(next.index));
      if (visited[size_t(next.index)])
        throw_input(name_, next.from,
                    path +
                        " is reached a second time (a cycle, or a second parent); expected the "
                        "node hierarchy to be a set of trees");
      visited[size_t(next.index)] = true;
      const tinygltf::Node& node = model_.nodes[size_t(next.index)];
      Trs rest;
      const Transform local = local_transform(node, path, rest);
      const Transform world = next.parent * local;
      if (!world.is_finite())
        throw_input(name_, path,
                    "the node's world transform overflows (its ancestors' scales multiply past "
                    "double range)");
      uint32_t scene_node = kNoNode;
      if (keep_nodes_)
        scene_node_[size_t(next.index)] = scene_node =
            scene_.hierarchy.add_node(next.parent_node, local, rest);
      uint32_t asset = next.asset;
      if (asset == kNoAsset) {  // a root: its tree's asset
        asset = uint32_t(scene_.assets.size());
        scene_.assets.push_back(node.name.empty() ? path : node.name);
      }
      visit(node, path, world, scene_node, asset);
      for (size_t c = node.children.size(); c-- > 0;)
        stack.push_back(
            {node.children[c], world, scene_node, path + "." + index_path("children", c), asset});
    }
    // Without a scene every node is drawn; one that no root reaches hangs below a cycle.
    if (model_.scenes.empty())
      for (size_t i = 0; i < visited.size(); ++i)
        if (!visited[i])
          throw_input(name_, index_path("nodes", i),
                      "no root above this node: its ancestors form a cycle; expected the node "
                      "hierarchy to be a set of trees");
  }

  // `scene_node` is the node's index in scene_.hierarchy, kNoNode when the file cannot move it;
  // `asset` its tree's root in scene_.assets.
  void visit(const tinygltf::Node& node, const std::string& path, const Transform& world,
             uint32_t scene_node, uint32_t asset) {
    if (auto surface = gltf::read_node_subdivision(model_, node, path, world, scene_node,
                                                   scene_.materials, name_, diagnostics_)) {
      for (SubdivisionPart& part : surface->parts)
        if (part.material == gltf::kNoSubdivisionMaterial) part.material = default_material();
      surface->asset = asset;
      scene_.subdivision_surfaces.push_back(std::move(*surface));
    } else if (node.mesh >= 0 && (node.skin >= 0 || has_morph_targets(node_mesh(node, path)) ||
                                  node.extensions.count("FILMBACK_deformation"))) {
      add_deformed_mesh(node, path, world, scene_node, asset);
    } else if (node.mesh >= 0) {
      add_mesh(node, path, world, scene_node, asset);
    }
    if (node.camera >= 0)
      scene_.cameras.push_back(gltf::read_camera(model_, node, path, world, scene_node,
                                                 scene_.settings, name_, diagnostics_));
    gltf::read_node_light(model_, node, path, world, scene_node, name_, scene_, diagnostics_);
  }

  const tinygltf::Mesh& node_mesh(const tinygltf::Node& node, const std::string& path) {
    if (size_t(node.mesh) >= model_.meshes.size())
      throw_input(name_, path + ".mesh",
                  out_of_range("mesh", node.mesh, model_.meshes.size(), "meshes"));
    return model_.meshes[size_t(node.mesh)];
  }

  std::string primitive_path(const tinygltf::Node& node, size_t p) {
    return index_path("meshes", size_t(node.mesh)) + "." + index_path("primitives", p);
  }

  static bool has_morph_targets(const tinygltf::Mesh& mesh) {
    for (const tinygltf::Primitive& p : mesh.primitives)
      if (!p.targets.empty()) return true;
    return false;
  }

  // Each primitive of a skinned, morphed or evaluated node becomes a mesh of its own, posed by
  // the render and never shared with another node (the node's weights may differ from
  // another's). glTF 2.0 §3.8.3: the joints place a skinned mesh, not its node, so it is drawn at
  // the identity; so is an evaluated one whose shapes are in world space. Evaluated shapes
  // (FILMBACK_deformation) replace the skin and the morph targets, which are not read.
  void add_deformed_mesh(const tinygltf::Node& node, const std::string& path,
                         const Transform& world, uint32_t scene_node, uint32_t asset) {
    const tinygltf::Mesh& mesh = node_mesh(node, path);
    gltf::check_instance_count(scene_.instances.size(), mesh.primitives.size(), name_,
                               path + ".mesh");
    const std::optional<gltf::NodeDeformation> evaluated =
        gltf::read_node_deformation(node, path, mesh.primitives.size(), name_);
    const bool skinned = evaluated ? evaluated->world_space : node.skin >= 0;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      const std::string ppath = primitive_path(node, p);
      std::optional<TriangleMesh> converted = convert_primitive(mesh, prim, ppath);
      if (!converted) continue;
      Deformed d;
      d.node = size_t(&node - model_.nodes.data());
      d.deformation.mesh = uint32_t(scene_.meshes.size());
      if (evaluated)
        d.deformation.evaluated =
            gltf::read_evaluated_shapes(model_, *evaluated, p, converted->positions.size(), name_);
      else if (!prim.targets.empty())
        d.deformation.morph = gltf::read_morph_targets(
            model_, node, path, mesh, prim, ppath, converted->positions.size(),
            !converted->texturing.tangents.empty(), name_);
      if (node.skin >= 0 && !evaluated)
        d.skin = {node.skin, path + ".skin", &prim, ppath, converted->positions.size()};
      scene_.instances.push_back({d.deformation.mesh, skinned ? Transform() : world,
                                  node.name.empty() ? path : node.name,
                                  skinned ? kNoNode : scene_node, asset});
      scene_.meshes.push_back(std::move(*converted));
      deformed_.push_back(std::move(d));
    }
  }

  void add_mesh(const tinygltf::Node& node, const std::string& path, const Transform& world,
                uint32_t scene_node, uint32_t asset) {
    const tinygltf::Mesh& mesh = node_mesh(node, path);
    // The node's own placement, or one per EXT_mesh_gpu_instancing instance in the node's space.
    std::vector<Transform> placements{world};
    if (auto node_from_instance =
            gltf::read_gpu_instances(model_, node, path, name_, scene_.instances.size())) {
      placements.clear();
      for (const Transform& t : *node_from_instance)
        placements.push_back(world * t);
    }
    // Bounded before it is made: a few thousand primitives drawn by a few thousand nodes would
    // otherwise make 10^7 instances from a file of kilobytes.
    gltf::check_instance_count(scene_.instances.size(), placements.size() * mesh.primitives.size(),
                               name_, path + ".mesh");
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const auto key = std::pair{node.mesh, p};
      auto cached = primitive_meshes_.find(key);
      if (cached == primitive_meshes_.end()) {
        const std::string ppath = primitive_path(node, p);
        std::optional<TriangleMesh> converted = convert_primitive(mesh, mesh.primitives[p], ppath);
        std::optional<uint32_t> index;
        if (converted) {
          index = uint32_t(scene_.meshes.size());
          scene_.meshes.push_back(std::move(*converted));
        }
        cached = primitive_meshes_.emplace(key, index).first;
      }
      if (cached->second)
        for (const Transform& placement : placements)
          scene_.instances.push_back({*cached->second, placement,
                                      node.name.empty() ? path : node.name, scene_node, asset});
    }
  }

  std::optional<TriangleMesh> convert_primitive(const tinygltf::Mesh& mesh,
                                                const tinygltf::Primitive& prim,
                                                const std::string& path) {
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      warn(path + ".mode",
           "points and lines (mode " + std::to_string(mode) + ") are not supported yet; skipped");
      return std::nullopt;
    }
    const auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end())
      throw_input(name_, path + ".attributes", "a triangle primitive needs POSITION");
    const gltf::AccessorContext ctx{model_, name_};
    TriangleMesh out;
    out.name = mesh.name.empty() ? path : mesh.name;
    out.positions = gltf::read_vec3(ctx, position->second, path + ".attributes.POSITION");
    if (const auto normal = prim.attributes.find("NORMAL"); normal != prim.attributes.end()) {
      out.normals = gltf::read_vec3(ctx, normal->second, path + ".attributes.NORMAL");
      if (out.normals.size() != out.positions.size())
        throw_input(name_, path + ".attributes.NORMAL",
                    std::to_string(out.normals.size()) + " normals for " +
                        std::to_string(out.positions.size()) + " positions");
    }
    std::vector<uint32_t> vertices;
    if (prim.indices >= 0) {
      vertices = gltf::read_indices(ctx, prim.indices, path + ".indices", out.positions.size());
    } else {
      vertices.resize(out.positions.size());
      for (size_t i = 0; i < vertices.size(); ++i)
        vertices[i] = uint32_t(i);
    }
    out.indices = triangle_list(vertices, mode, path);
    if (prim.material >= 0) {
      // Against the file's materials, not scene_.materials, which may also hold the default one.
      if (size_t(prim.material) >= model_.materials.size())
        throw_input(name_, path + ".material",
                    out_of_range("material", prim.material, model_.materials.size(), "materials"));
      out.material = uint32_t(prim.material);
    } else {
      out.material = default_material();
    }
    static const tinygltf::Value kNone;
    const auto ours = mesh.extensions.find("FILMBACK_blender");
    const gltf::Fields mesh_extension(
        ours == mesh.extensions.end() ? kNone : ours->second,
        index_path("meshes", size_t(&mesh - model_.meshes.data())) + ".extensions.FILMBACK_blender",
        name_);
    gltf::read_texturing(ctx, prim, path, scene_.materials[out.material], mesh_extension, out,
                         diagnostics_);
    return out;
  }

  // glTF §3.7.2.1: lists, strips (winding alternates) and fans, all as counter-clockwise lists.
  std::vector<uint32_t> triangle_list(const std::vector<uint32_t>& v, int mode,
                                      const std::string& path) {
    std::vector<uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (v.size() % 3 != 0)
        warn(path,
             std::to_string(v.size() % 3) + " trailing vertices do not form a triangle; ignored");
      out.assign(v.begin(), v.begin() + ptrdiff_t(v.size() - v.size() % 3));
      return out;
    }
    for (size_t i = 2; i < v.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
        out.insert(out.end(), {v[0], v[i - 1], v[i]});
      else if (i % 2 == 0)
        out.insert(out.end(), {v[i - 2], v[i - 1], v[i]});
      else
        out.insert(out.end(), {v[i - 1], v[i - 2], v[i]});
    }
    return out;
  }

  fs::path file_;
  std::string name_;
  Diagnostics& diagnostics_;
  tinygltf::Model model_;
  Scene scene_;
  std::optional<uint32_t> default_material_;
  std::map<std::pair<int, size_t>, std::optional<uint32_t>> primitive_meshes_;
  bool keep_nodes_ = false;
  std::vector<uint32_t> scene_node_;  // glTF node -> scene_.hierarchy index, when keep_nodes_
  // A skinned or morphed primitive until the walk is done: its glTF node and skin.
  struct Deformed {
    MeshDeformation deformation;
    size_t node = 0;
    gltf::SkinSource skin;  // skin -1: not skinned
  };
  std::vector<Deformed> deformed_;
};

}  // namespace

Scene import_gltf(const fs::path& file, Diagnostics& diagnostics) {
  return Importer(file, diagnostics).run();
}

}  // namespace fb
