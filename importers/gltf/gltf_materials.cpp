#include "importers/gltf/gltf_materials.h"

#include <tiny_gltf.h>

#include <cmath>
#include <numbers>

#include "core/scene/mesh_tangents.h"
#include "core/texture/graph_shader.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_blender_material.h"
#include "importers/gltf/gltf_json.h"
#include "importers/gltf/gltf_povray_pattern.h"

namespace fb::gltf {
namespace {

// A base colour factor beyond glTF's [0, 1] (a POV-Ray pigment brighter than white, or
// diffuse above 1): single precision keeps it finite.
constexpr double kLargestFactor = 1e6;

class MaterialReader {
 public:
  MaterialReader(const tinygltf::Model& model, const std::string& file, Diagnostics& diagnostics)
      : model_(model), file_(file), diagnostics_(diagnostics) {}

  Material read(const tinygltf::Material& g, const std::string& path) {
    Material m;
    m.name = g.name.empty() ? path : g.name;
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    const std::string pbr_path = path + ".pbrMetallicRoughness";
    if (pbr.baseColorFactor.size() == 4) {
      for (size_t c = 0; c < 4; ++c)
        if (!(pbr.baseColorFactor[c] >= 0 && pbr.baseColorFactor[c] <= 1))
          throw_input(file_, pbr_path + ".baseColorFactor", "expected components in [0, 1]");
      m.base_color = Rgb(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                         float(pbr.baseColorFactor[2]));
      m.alpha = float(pbr.baseColorFactor[3]);
    }
    m.metallic = unit_factor(pbr.metallicFactor, pbr_path + ".metallicFactor");
    m.roughness = unit_factor(pbr.roughnessFactor, pbr_path + ".roughnessFactor");
    m.textures.base_color = texture(pbr.baseColorTexture, pbr_path + ".baseColorTexture");
    m.textures.metallic_roughness =
        texture(pbr.metallicRoughnessTexture, pbr_path + ".metallicRoughnessTexture");
    m.textures.normal = texture(g.normalTexture, path + ".normalTexture");
    m.textures.normal_scale = float(g.normalTexture.scale);
    if (!std::isfinite(m.textures.normal_scale))
      throw_input(file_, path + ".normalTexture.scale", "expected a finite number");
    m.textures.emissive = texture(g.emissiveTexture, path + ".emissiveTexture");
    if (g.occlusionTexture.index >= 0)
      warn(path + ".occlusionTexture",
           "ignored: ambient occlusion is what the path tracer computes (glTF allows this)");

    const double strength = extension_fields(g.extensions, "KHR_materials_emissive_strength", path)
                                .number("emissiveStrength", 0, HUGE_VAL)
                                .value_or(1.0);
    if (g.emissiveFactor.size() == 3)
      m.emission = Rgb(float(g.emissiveFactor[0] * strength), float(g.emissiveFactor[1] * strength),
                       float(g.emissiveFactor[2] * strength));
    if (!(min_component(m.emission) >= 0 && is_finite(m.emission)))
      throw_input(file_, path,
                  "emission (emissiveFactor x emissiveStrength) must be finite and non-negative");
    m.double_sided = g.doubleSided;

    const Fields transmission = extension_fields(g.extensions, "KHR_materials_transmission", path);
    m.transmission = float(transmission.number("transmissionFactor", 0, 1).value_or(0.0));
    if (transmission.has("transmissionTexture"))
      warn(transmission.path() + ".transmissionTexture",
           "not supported yet; transmissionFactor used");
    // The extension allows 0 for "no refraction" (F0 = 1); filmback keeps real materials only.
    m.ior = float(extension_fields(g.extensions, "KHR_materials_ior", path)
                      .number("ior", 1, 10)
                      .value_or(1.5));
    // FILMBACK_povray's specular_factor is the exact one, KHR's the colour other viewers read
    // (gltf_writer.cpp, khr_specular_for_viewers).
    const Fields pov = extension_fields(g.extensions, "FILMBACK_povray", path);
    const Fields specular = extension_fields(g.extensions, "KHR_materials_specular", path);
    if (const std::optional<double> exact = pov.number("specular_factor", 0, 1)) {
      m.specular = float(*exact);
    } else {
      m.specular = float(specular.number("specularFactor", 0, 1).value_or(1.0));
      // With specularFactor 0 there is no specular layer, whatever its colour.
      if (const std::optional<Rgb> colour = specular.color("specularColorFactor");
          colour && m.specular > 0)
        fold_specular_colour(*colour, specular.path() + ".specularColorFactor", m);
    }
    if (specular.has("specularTexture") || specular.has("specularColorTexture"))
      warn(specular.path(), "specular textures are not supported yet; the factors are used");

    if (g.alphaMode == "MASK") {
      m.alpha_mode = AlphaMode::kMask;
      if (!(g.alphaCutoff >= 0 && std::isfinite(g.alphaCutoff)))
        throw_input(file_, path + ".alphaCutoff", "expected a finite number >= 0");
      m.alpha_cutoff = float(g.alphaCutoff);
    } else if (g.alphaMode == "BLEND") {
      m.alpha_mode = AlphaMode::kBlend;
    } else if (!g.alphaMode.empty() && g.alphaMode != "OPAQUE") {
      throw_input(file_, path + ".alphaMode",
                  "'" + g.alphaMode + "' is not an alpha mode (expected OPAQUE, MASK or BLEND)");
    }
    // A POV-Ray pigment and the exact base colour factor (docs/pov.md "Conversion").
    if (pov.has("pigment")) m.base_color_pattern = read_pattern(pov.object("pigment"));
    if (const auto factor = pov.numbers("base_color_factor", 3, 0, kLargestFactor)) {
      if (factor->size() != 3) pov.fail("base_color_factor", "expected [r, g, b]");
      m.base_color = Rgb(float((*factor)[0]), float((*factor)[1]), float((*factor)[2]));
    }
    // The emission before the pigment multiplies it (emissiveFactor is after, for other viewers).
    if (const auto factor = pov.numbers("emission_factor", 3, 0, kLargestFactor)) {
      if (factor->size() != 3) pov.fail("emission_factor", "expected [r, g, b]");
      if (!m.base_color_pattern) pov.fail("emission_factor", "expected beside a pigment");
      m.emission = Rgb(float((*factor)[0]), float((*factor)[1]), float((*factor)[2]));
    }
    // Fully covered everywhere: no need to test each hit.
    if (m.alpha_mode == AlphaMode::kBlend && m.alpha >= 1 && !m.textures.base_color.present() &&
        !m.base_color_pattern)
      m.alpha_mode = AlphaMode::kOpaque;
    return m;
  }

 private:
  void warn(const std::string& where, const std::string& what) {
    diagnostics_.warn(located(file_, where, what));
  }

  // KHR_materials_specular: F0 = min(((ior - 1) / (ior + 1))^2 specularColorFactor, 1). Blender
  // writes Principled's Specular s so (F0 = 0.08 s at its IOR). For an opaque material ior matters
  // only through F0, so the colour (grey: the BSDF's Fresnel is scalar) folds into the index that
  // gives the same F0; a transmissive material keeps its ior, which refraction needs.
  void fold_specular_colour(Rgb c, const std::string& where, Material& m) {
    if (c.x != c.y || c.y != c.z)
      warn(where, "a coloured specular is carried as its luminance (the Fresnel term is grey)");
    const double grey = luminance(c);
    if (grey == 1) return;
    if (m.transmission > 0) {
      warn(where, "not carried on a transmissive material (its ior also sets refraction)");
      return;
    }
    const double r = (m.ior - 1) / (m.ior + 1);
    // Below 1, so the index stays finite (F0 = 0.99: ior 399).
    const double root_f0 = std::sqrt(std::min(r * r * grey, 0.99));
    m.ior = float((1 + root_f0) / (1 - root_f0));
  }

  float unit_factor(double v, const std::string& where) {
    if (!(v >= 0 && v <= 1))
      throw_input(file_, where, number_text(v) + ", expected a value in [0, 1]");
    return float(v);
  }

  // The members of extension `name` of an object at JSON path `path` (none when it is absent).
  Fields extension_fields(const tinygltf::ExtensionMap& map, const char* name,
                          const std::string& path) const {
    static const tinygltf::Value kAbsent;
    const auto it = map.find(name);
    return Fields(it == map.end() ? kAbsent : it->second, path + ".extensions." + name, file_);
  }

  // A textureInfo (glTF 2.0 §5.29) with its sampler's wrap modes and KHR_texture_transform.
  template <typename Info>
  TextureRef texture(const Info& info, const std::string& where) {
    TextureRef ref;
    if (info.index < 0) return ref;
    if (size_t(info.index) >= model_.textures.size())
      throw_input(file_, where + ".index",
                  out_of_range("texture", info.index, model_.textures.size(), "textures"));
    const std::string t_path = index_path("textures", size_t(info.index));
    const tinygltf::Texture& t = model_.textures[size_t(info.index)];
    if (t.source < 0 || size_t(t.source) >= model_.images.size())
      throw_input(file_, t_path + ".source",
                  "expected an image index below " + std::to_string(model_.images.size()) +
                      " (texture extensions such as KHR_texture_basisu are not supported)");
    ref.image = uint32_t(t.source);
    if (info.texCoord < 0 || uint32_t(info.texCoord) >= VertexTextureData::kSets)
      throw_input(file_, where + ".texCoord", "expected 0 or 1 (TEXCOORD_0 or TEXCOORD_1)");
    ref.texcoord = uint32_t(info.texCoord);
    if (t.sampler >= 0) {
      if (size_t(t.sampler) >= model_.samplers.size())
        throw_input(file_, t_path + ".sampler", "sampler index out of range");
      const tinygltf::Sampler& s = model_.samplers[size_t(t.sampler)];
      ref.wrap_s = wrap(s.wrapS), ref.wrap_t = wrap(s.wrapT);
    }
    transform(extension_fields(info.extensions, "KHR_texture_transform", where), ref);
    return ref;
  }

  static TextureWrap wrap(int mode) {
    if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::kClamp;
    if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::kMirror;
    return TextureWrap::kRepeat;
  }

  // KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv, with R = [c s; -s c]
  // (the extension's README, "transform").
  void transform(const Fields& e, TextureRef& ref) {
    auto pair = [&](const char* key, double fallback) -> std::array<double, 2> {
      const auto v = e.numbers(key, 2, -HUGE_VAL, HUGE_VAL);
      if (!v) return {fallback, fallback};
      if (v->size() != 2 || !std::isfinite((*v)[0]) || !std::isfinite((*v)[1]))
        e.fail(key, "expected two finite numbers");
      return {(*v)[0], (*v)[1]};
    };
    const auto offset = pair("offset", 0.0), scale = pair("scale", 1.0);
    const double rotation = e.number("rotation", -HUGE_VAL, HUGE_VAL).value_or(0.0);
    if (!std::isfinite(rotation)) e.fail("rotation", "expected a finite number");
    const double c = std::cos(rotation), s = std::sin(rotation);
    ref.uv_transform = {float(c * scale[0]),  float(s * scale[1]), float(offset[0]),
                        float(-s * scale[0]), float(c * scale[1]), float(offset[1])};
    if (const auto tc = e.whole("texCoord", 0, VertexTextureData::kSets - 1))
      ref.texcoord = uint32_t(*tc);
  }

  const tinygltf::Model& model_;
  const std::string& file_;
  Diagnostics& diagnostics_;
};

}  // namespace

void read_materials(tinygltf::Model& model, const std::string& file, Scene& scene,
                    Diagnostics& diagnostics) {
  MaterialReader reader(model, file, diagnostics);
  for (size_t i = 0; i < model.materials.size(); ++i)
    scene.materials.push_back(reader.read(model.materials[i], index_path("materials", i)));
  std::vector<bool> used(model.images.size(), false);
  for (const Material& m : scene.materials)
    for (const TextureRef* t : {&m.textures.base_color, &m.textures.metallic_roughness,
                                &m.textures.normal, &m.textures.emissive})
      if (t->present()) used[t->image] = true;
  for (size_t i = 0; i < model.images.size(); ++i) {
    tinygltf::Image& g = model.images[i];
    // tinygltf only warns about an image it could not read; a material needs it.
    if (used[i] && g.image.empty())
      throw_input(file, index_path("images", i) + (g.uri.empty() ? ".bufferView" : ".uri"),
                  g.uri.empty() || g.uri.rfind("data:", 0) == 0
                      ? "no image data"
                      : "'" + g.uri +
                            "' could not be read (expected a regular file inside the scene's "
                            "folder, at most 2 GiB)");
    TextureImage image;
    image.name =
        index_path("images", i) +
        (g.uri.empty() || g.uri.rfind("data:", 0) == 0 ? std::string() : " (" + g.uri + ")");
    image.bytes = std::move(g.image);
    scene.images.push_back(std::move(image));
  }
  // After the file's images, whose indices the glTF textures use.
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const auto ext = model.materials[i].extensions.find("FILMBACK_blender");
    if (ext == model.materials[i].extensions.end()) continue;
    const Fields fields(ext->second, index_path("materials", i) + ".extensions.FILMBACK_blender",
                        file);
    Material& m = scene.materials[i];
    m.shader_graph = read_shader_graph(fields, scene, diagnostics);
    m.emission = GraphShader::emission_bound(*m.shader_graph);
    m.double_sided = true;
    m.alpha_mode =
        GraphShader::can_be_transparent(*m.shader_graph) ? AlphaMode::kBlend : AlphaMode::kOpaque;
  }
}

namespace {

// TEXCOORD_n of a primitive, or nothing when it has none.
std::vector<Vec2f> read_texcoords(const AccessorContext& ctx, const tinygltf::Primitive& prim,
                                  const std::string& path, uint32_t n, size_t vertex_count) {
  const std::string name = "TEXCOORD_" + std::to_string(n);
  const auto it = prim.attributes.find(name);
  if (it == prim.attributes.end()) return {};
  const std::string where = path + ".attributes." + name;
  const std::vector<double> values =
      read_animation_values(ctx, it->second, where, TINYGLTF_TYPE_VEC2, true);
  if (values.size() != 2 * vertex_count)
    throw_input(ctx.file, where,
                std::to_string(values.size() / 2) + " texture coordinates for " +
                    std::to_string(vertex_count) + " positions");
  std::vector<Vec2f> uv(vertex_count);
  for (size_t v = 0; v < vertex_count; ++v)
    uv[v] = {float(values[2 * v]), float(values[2 * v + 1])};
  return uv;
}

}  // namespace

TexcoordPlan plan_texcoords(const Material& material, const MeshUvMaps& maps,
                            const std::string& file, const std::string& path,
                            Diagnostics& diagnostics) {
  TexcoordPlan plan;
  if (material.shader_graph) {
    // The graph's UV maps, found by name, in the graph's slots.
    const ShaderGraph& graph = *material.shader_graph;
    for (size_t slot = 0; slot < graph.uv_maps.size(); ++slot) {
      const std::string& name = graph.uv_maps[slot];
      plan.slots[slot] = maps.texcoord(name);
      if (!plan.slots[slot]) {
        diagnostics.warn(located(file, path,
                                 "the mesh has no UV map '" + name + "' that material '" +
                                     material.name + "' reads; TEXCOORD_0 is used"));
        plan.slots[slot] = 0;
      }
    }
    if (graph.has_normal_map) plan.tangent_slot = graph.normal_map_uv_slot;
    return plan;
  }
  if (!material.textures.any() && material.alpha_mode == AlphaMode::kOpaque) return plan;
  for (uint32_t set = 0; set < VertexTextureData::kSets; ++set)
    plan.slots[set] = set;
  const MaterialTextures& t = material.textures;
  for (const TextureRef* ref : {&t.base_color, &t.metallic_roughness, &t.normal, &t.emissive})
    if (ref->present()) plan.required[ref->texcoord] = true;
  if (t.normal.present()) plan.tangent_slot = t.normal.texcoord;
  return plan;
}

void read_texturing(const AccessorContext& ctx, const tinygltf::Primitive& prim,
                    const std::string& path, const Material& material, const Fields& mesh_extension,
                    TriangleMesh& mesh, Diagnostics& diagnostics) {
  const TexcoordPlan plan =
      plan_texcoords(material, read_mesh_uv_maps(mesh_extension), ctx.file, path, diagnostics);
  VertexTextureData& out = mesh.texturing;
  if (material.shader_graph && material.shader_graph->needs_radial_tangent)
    out.radial_tangents = radial_tangents(mesh.positions, mesh_extension);
  for (uint32_t slot = 0; slot < VertexTextureData::kSets; ++slot) {
    if (!plan.slots[slot]) continue;
    const uint32_t n = *plan.slots[slot];
    out.texcoords[slot] = read_texcoords(ctx, prim, path, n, mesh.positions.size());
    if (out.texcoords[slot].empty() && plan.required[slot])
      throw_input(ctx.file, path + ".attributes",
                  "material '" + material.name + "' reads TEXCOORD_" + std::to_string(n) +
                      ", which the primitive does not have");
    if (out.texcoords[slot].empty() && material.shader_graph)
      diagnostics.warn(located(ctx.file, path + ".attributes",
                               "no TEXCOORD_" + std::to_string(n) + " for UV map '" +
                                   material.shader_graph->uv_maps[slot] +
                                   "': its textures read the point (0, 0)"));
  }
  if (!plan.tangent_slot) return;
  if (const auto it = prim.attributes.find("TANGENT");
      it != prim.attributes.end() && !material.shader_graph) {
    const std::string where = path + ".attributes.TANGENT";
    const std::vector<double> values =
        read_animation_values(ctx, it->second, where, TINYGLTF_TYPE_VEC4, false);
    if (values.size() != 4 * mesh.positions.size())
      throw_input(ctx.file, where,
                  std::to_string(values.size() / 4) + " tangents for " +
                      std::to_string(mesh.positions.size()) + " positions");
    out.tangents.resize(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      out.tangents[v] = {float(values[4 * v]), float(values[4 * v + 1]), float(values[4 * v + 2]),
                         values[4 * v + 3] < 0 ? -1.f : 1.f};
  } else if (!out.texcoords[*plan.tangent_slot].empty()) {
    out.tangents = mesh_tangents(mesh, out.texcoords[*plan.tangent_slot]);
  }
}

}  // namespace fb::gltf
