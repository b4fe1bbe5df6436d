#include "importers/gltf/gltf_blender_material.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/util/error.h"
#include "importers/gltf/gltf_file.h"

namespace fb::gltf {
namespace {

// Bounds on what an untrusted file may ask for.
constexpr size_t kMaxNodes = 1024;
constexpr size_t kMaxWarnings = 1024;
constexpr double kLargestValue = 1e30;  // beyond it single precision is not finite

struct SocketName {
  const char* key;
  Socket socket;
};
constexpr SocketName kSockets[] = {
    {"base_color", Socket::kBaseColor},
    {"subsurface", Socket::kSubsurface},
    {"subsurface_radius", Socket::kSubsurfaceRadius},
    {"subsurface_color", Socket::kSubsurfaceColor},
    {"subsurface_ior", Socket::kSubsurfaceIor},
    {"subsurface_anisotropy", Socket::kSubsurfaceAnisotropy},
    {"metallic", Socket::kMetallic},
    {"specular", Socket::kSpecular},
    {"specular_tint", Socket::kSpecularTint},
    {"roughness", Socket::kRoughness},
    {"anisotropic", Socket::kAnisotropic},
    {"anisotropic_rotation", Socket::kAnisotropicRotation},
    {"sheen", Socket::kSheen},
    {"sheen_tint", Socket::kSheenTint},
    {"clearcoat", Socket::kClearcoat},
    {"clearcoat_roughness", Socket::kClearcoatRoughness},
    {"ior", Socket::kIor},
    {"transmission", Socket::kTransmission},
    {"transmission_roughness", Socket::kTransmissionRoughness},
    {"emission", Socket::kEmission},
    {"emission_strength", Socket::kEmissionStrength},
    {"alpha", Socket::kAlpha},
    {"normal", Socket::kNormal},
    {"clearcoat_normal", Socket::kClearcoatNormal},
    {"tangent", Socket::kTangent},
    {"color", Socket::kColor},
    {"strength", Socket::kStrength},
    {"fac", Socket::kFac},
};

enum class ValueKind { kNumber, kTriple, kNormal };

ValueKind kind_of(Socket s) {
  switch (s) {
    case Socket::kBaseColor:
    case Socket::kSubsurfaceRadius:
    case Socket::kSubsurfaceColor:
    case Socket::kEmission:
    case Socket::kColor:
      return ValueKind::kTriple;
    case Socket::kNormal:
    case Socket::kClearcoatNormal:
    case Socket::kTangent:
      return ValueKind::kNormal;
    default:
      return ValueKind::kNumber;
  }
}

struct NodeKind {
  const char* name;
  ShaderNodeType type;
  std::vector<Socket> sockets;
  // Cycles' value for an input the file leaves out: the node's default in Blender 3.4.
  std::vector<std::pair<Socket, Vec3f>> defaults;
};

const std::vector<NodeKind>& node_kinds() {
  static const std::vector<NodeKind> kinds = [] {
    std::vector<Socket> principled;
    for (int s = 0; s <= int(Socket::kTangent); ++s)
      principled.push_back(Socket(s));
    const Vec3f grey{0.8f, 0.8f, 0.8f};
    return std::vector<NodeKind>{
        {"PRINCIPLED",
         ShaderNodeType::kPrincipled,
         principled,
         {{Socket::kBaseColor, grey},
          {Socket::kSubsurfaceRadius, {1.f, 0.2f, 0.1f}},
          {Socket::kSubsurfaceColor, grey},
          {Socket::kSubsurfaceIor, {1.4f, 0, 0}},
          {Socket::kSpecular, {0.5f, 0, 0}},
          {Socket::kRoughness, {0.5f, 0, 0}},
          {Socket::kSheenTint, {0.5f, 0, 0}},
          {Socket::kClearcoatRoughness, {0.03f, 0, 0}},
          {Socket::kIor, {1.45f, 0, 0}},
          {Socket::kEmissionStrength, {1.f, 0, 0}},
          {Socket::kAlpha, {1.f, 0, 0}}}},
        {"DIFFUSE",
         ShaderNodeType::kDiffuse,
         {Socket::kColor, Socket::kRoughness, Socket::kNormal},
         {{Socket::kColor, grey}}},
        {"GLOSSY",
         ShaderNodeType::kGlossy,
         {Socket::kColor, Socket::kRoughness, Socket::kNormal},
         {{Socket::kColor, grey}, {Socket::kRoughness, {0.5f, 0, 0}}}},
        {"GLASS",
         ShaderNodeType::kGlass,
         {Socket::kColor, Socket::kRoughness, Socket::kIor, Socket::kNormal},
         {{Socket::kColor, {1.f, 1.f, 1.f}}, {Socket::kIor, {1.45f, 0, 0}}}},
        {"EMISSION",
         ShaderNodeType::kEmission,
         {Socket::kColor, Socket::kStrength},
         {{Socket::kColor, {1.f, 1.f, 1.f}}, {Socket::kStrength, {1.f, 0, 0}}}},
        {"TRANSPARENT",
         ShaderNodeType::kTransparent,
         {Socket::kColor},
         {{Socket::kColor, {1.f, 1.f, 1.f}}}},
        {"MIX_SHADER", ShaderNodeType::kMix, {Socket::kFac}, {{Socket::kFac, {0.5f, 0, 0}}}},
        {"ADD_SHADER", ShaderNodeType::kAdd, {}, {}},
    };
  }();
  return kinds;
}

class GraphReader {
 public:
  GraphReader(const Fields& extension, Scene& scene, Diagnostics& diagnostics)
      : ext_(extension), scene_(scene), diagnostics_(diagnostics) {}

  ShaderGraph read() {
    for (const std::string& w :
         ext_.words("warnings", kMaxWarnings).value_or(std::vector<std::string>{}))
      diagnostics_.warn(located(ext_.file(), ext_.path(), "from Blender: " + w));
    read_version();
    const std::vector<Fields> nodes = ext_.objects("nodes", kMaxNodes);
    graph_.nodes.resize(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i)
      read_node(nodes[i], graph_.nodes[i]);
    if (const auto surface = ext_.whole("surface", 0, double(nodes.size()) - 1))
      graph_.surface = uint32_t(*surface);
    check_acyclic();
    for (size_t i = 0; i < graph_.nodes.size(); ++i) {
      const ShaderNode& node = graph_.nodes[i];
      if (node.type != ShaderNodeType::kPrincipled) continue;
      if (varies_or_nonzero(node.in(Socket::kAnisotropic))) graph_.needs_radial_tangent = true;
      if (varies_or_nonzero(node.in(Socket::kSubsurface)))
        warn(ext_.path() + "." + index_path("nodes", i) + ".inputs.subsurface",
             "'" + node.name +
                 "': subsurface scattering renders as its diffuse fallback (the Principled "
                 "diffuse of the base and subsurface colours mixed by Subsurface; docs/blender.md)");
    }
    return std::move(graph_);
  }

 private:
  // Blender 4.0 replaced the Principled BSDF (v2: another layering, new sockets); filmback
  // renders Cycles 3.4's nodes.
  void read_version() {
    const auto v = ext_.numbers("blender_version", 3, 0, 1e6);
    if (!v || v->size() != 3) return;
    graph_.blender_version = std::to_string(long((*v)[0])) + "." + std::to_string(long((*v)[1])) +
                             "." + std::to_string(long((*v)[2]));
    if ((*v)[0] >= 4)
      warn(ext_.path() + ".blender_version",
           "exported by Blender " + graph_.blender_version +
               ", whose shader nodes changed in 4.0; rendered as Cycles 3.4 renders its nodes");
  }

  void read_node(const Fields& f, ShaderNode& node) {
    const std::string type = f.word("type").value_or("");
    const auto kind = std::find_if(node_kinds().begin(), node_kinds().end(),
                                   [&](const NodeKind& k) { return type == k.name; });
    if (kind == node_kinds().end())
      f.fail("type",
             "'" + type +
                 "' is not a node type (expected PRINCIPLED, DIFFUSE, GLOSSY, GLASS, EMISSION, "
                 "TRANSPARENT, MIX_SHADER or ADD_SHADER)");
    node.type = kind->type;
    node.name = f.word("name").value_or(f.path());
    for (const auto& [socket, value] : kind->defaults)
      node.in(socket) = {ShaderInput::Kind::kConstant, value};
    if (node.type == ShaderNodeType::kPrincipled || node.type == ShaderNodeType::kGlossy ||
        node.type == ShaderNodeType::kGlass)
      node.distribution = distribution(f, node.type);
    if (node.type == ShaderNodeType::kPrincipled) node.subsurface_method = subsurface_method(f);
    if (node.type == ShaderNodeType::kMix || node.type == ShaderNodeType::kAdd) {
      const auto shaders = f.indices("shaders", 2, graph_.nodes.size());
      if (!shaders || shaders->size() != 2)
        f.fail("shaders", "expected [a, b]: two node indices (-1: unlinked)");
      for (int i = 0; i < 2; ++i)
        node.shaders[i] = (*shaders)[i] < 0 ? ShaderNode::kNone : uint32_t((*shaders)[i]);
    }
    const Fields inputs = f.object("inputs");
    for (const SocketName& s : kSockets) {
      if (!inputs.has(s.key)) continue;
      if (std::find(kind->sockets.begin(), kind->sockets.end(), s.socket) == kind->sockets.end())
        inputs.fail(s.key, std::string("a ") + kind->name + " node has no such input");
      node.in(s.socket) = input(inputs, s.key, kind_of(s.socket));
    }
  }

  static Distribution distribution(const Fields& f, ShaderNodeType type) {
    static const std::map<std::string, Distribution> kNames = {
        {"SHARP", Distribution::kSharp},
        {"BECKMANN", Distribution::kBeckmann},
        {"GGX", Distribution::kGgx},
        {"ASHIKHMIN_SHIRLEY", Distribution::kAshikhminShirley},
        {"MULTI_GGX", Distribution::kMultiGgx}};
    const std::string name = f.word("distribution").value_or("GGX");
    const auto it = kNames.find(name);
    const bool principled = type == ShaderNodeType::kPrincipled;
    if (it == kNames.end() ||
        (principled && it->second != Distribution::kGgx && it->second != Distribution::kMultiGgx) ||
        (type == ShaderNodeType::kGlass && it->second == Distribution::kAshikhminShirley))
      f.fail(
          "distribution",
          "'" + name + "' is not a distribution of this node (expected " +
              (principled
                   ? "GGX or MULTI_GGX"
                   : "SHARP, BECKMANN, GGX" +
                         std::string(type == ShaderNodeType::kGlossy ? ", ASHIKHMIN_SHIRLEY" : "") +
                         " or MULTI_GGX") +
              ")");
    return it->second;
  }

  static SubsurfaceMethod subsurface_method(const Fields& f) {
    const std::string name = f.word("subsurface_method").value_or("RANDOM_WALK");
    if (name == "BURLEY") return SubsurfaceMethod::kBurley;
    if (name == "RANDOM_WALK") return SubsurfaceMethod::kRandomWalk;
    if (name == "RANDOM_WALK_FIXED_RADIUS") return SubsurfaceMethod::kRandomWalkFixedRadius;
    f.fail("subsurface_method", "expected BURLEY, RANDOM_WALK or RANDOM_WALK_FIXED_RADIUS");
  }

  ShaderInput input(const Fields& inputs, const char* key, ValueKind kind) {
    ShaderInput in;
    switch (inputs.type(key)) {
      case Fields::Type::kNumber:
        if (kind != ValueKind::kNumber) break;
        in.kind = ShaderInput::Kind::kConstant;
        in.value.x = float(finite(inputs.number(key, -kLargestValue, kLargestValue)));
        return in;
      case Fields::Type::kArray: {
        if (kind != ValueKind::kTriple) break;
        const auto v = inputs.numbers(key, 3, -kLargestValue, kLargestValue);
        if (v->size() != 3) inputs.fail(key, "expected [r, g, b]");
        in.kind = ShaderInput::Kind::kConstant;
        in.value = Vec3f(float((*v)[0]), float((*v)[1]), float((*v)[2]));
        return in;
      }
      case Fields::Type::kObject: {
        const Fields f = inputs.object(key);
        if (kind == ValueKind::kNormal) return normal_map(f);
        in.kind = ShaderInput::Kind::kTexture;
        in.texture = texture(f.object("texture"));
        in.output = output(f);
        return in;
      }
      default:
        break;
    }
    inputs.fail(key, kind == ValueKind::kNumber   ? "expected a number or a texture"
                     : kind == ValueKind::kTriple ? "expected [r, g, b] or a texture"
                                                  : "expected a normal map");
  }

  static double finite(std::optional<double> v) { return v.value_or(0.0); }

  static TextureOutput output(const Fields& f) {
    const std::string out = f.word("output").value_or("Color");
    if (out != "Color" && out != "Alpha") f.fail("output", "expected Color or Alpha");
    const std::optional<std::string> channel = f.word("channel");
    if (!channel) return out == "Alpha" ? TextureOutput::kAlpha : TextureOutput::kColor;
    if (out == "Alpha") f.fail("channel", "a channel is taken from the Color output only");
    if (*channel == "R") return TextureOutput::kRed;
    if (*channel == "G") return TextureOutput::kGreen;
    if (*channel == "B") return TextureOutput::kBlue;
    f.fail("channel", "expected R, G or B");
  }

  ShaderInput normal_map(const Fields& f) {
    const Fields map = f.object("normal_map");
    if (!f.has("normal_map")) f.fail("normal_map", "expected a normal map object");
    ShaderInput in;
    in.kind = ShaderInput::Kind::kNormalMap;
    in.texture = texture(map.object("texture"));
    in.strength = float(map.number("strength", 0, kLargestValue).value_or(1.0));
    const std::string space = map.word("space").value_or("TANGENT");
    if (space != "TANGENT")
      warn(map.path() + ".space", "'" + space + "' normal maps are rendered as TANGENT ones");
    const uint32_t slot = uv_slot(map.word("uv_map").value_or(""), map.path() + ".uv_map");
    if (graph_.has_normal_map && slot != graph_.normal_map_uv_slot)
      warn(map.path() + ".uv_map",
           "normal maps on two UV maps: all take their tangents from the first one's");
    if (!graph_.has_normal_map) graph_.normal_map_uv_slot = slot;
    graph_.has_normal_map = true;
    return in;
  }

  uint32_t texture(const Fields& t) {
    if (!t.has("uri")) t.fail("uri", "expected the image file's name, relative to the scene file");
    ImageTextureNode node;
    node.image = image(*t.word("uri"), t.path() + ".uri");
    node.uv_slot = uv_slot(t.word("uv_map").value_or(""), t.path() + ".uv_map");
    if (const auto m = t.numbers("uv_transform", 6, -kLargestValue, kLargestValue)) {
      if (m->size() != 6) t.fail("uv_transform", "expected [a, b, c, d, e, f]");
      for (size_t i = 0; i < 6; ++i)
        node.uv_transform[i] = float((*m)[i]);
    }
    const std::string extension = t.word("extension").value_or("REPEAT");
    if (extension == "REPEAT")
      node.wrap = TextureWrap::kRepeat;
    else if (extension == "EXTEND")
      node.wrap = TextureWrap::kClamp;
    else if (extension == "CLIP")
      node.wrap = TextureWrap::kBlack;
    else if (extension == "MIRROR")
      node.wrap = TextureWrap::kMirror;
    else
      t.fail("extension", "expected REPEAT, EXTEND, CLIP or MIRROR");
    // Cycles' CPU image lookups treat Smart as Cubic (kernel/device/cpu/image.h).
    const std::string interpolation = t.word("interpolation").value_or("Linear");
    if (interpolation == "Linear")
      node.interpolation = TextureInterpolation::kLinear;
    else if (interpolation == "Closest")
      node.interpolation = TextureInterpolation::kClosest;
    else if (interpolation == "Cubic" || interpolation == "Smart")
      node.interpolation = TextureInterpolation::kCubic;
    else
      t.fail("interpolation", "expected Linear, Closest, Cubic or Smart");
    const std::string space = t.word("colorspace").value_or("sRGB");
    node.srgb = space == "sRGB";
    if (!node.srgb && space != "Non-Color" && space != "Linear" && space != "Raw")
      warn(t.path() + ".colorspace",
           "'" + space + "' images are read as linear values (only sRGB is decoded)");
    const std::string alpha = t.word("alpha_mode").value_or("STRAIGHT");
    node.ignore_alpha = alpha == "NONE";
    graph_.textures.push_back(node);
    return uint32_t(graph_.textures.size() - 1);
  }

  // The Scene::images entry for the file `uri` beside the scene, added once per file.
  uint32_t image(const std::string& uri, const std::string& where) {
    const std::filesystem::path file = confined_external_file(ext_.file(), uri, where);
    for (size_t i = 0; i < scene_.images.size(); ++i)
      if (scene_.images[i].file == file) return uint32_t(i);
    scene_.images.push_back({uri, file, {}});
    return uint32_t(scene_.images.size() - 1);
  }

  uint32_t uv_slot(const std::string& name, const std::string& where) {
    const auto it = std::find(graph_.uv_maps.begin(), graph_.uv_maps.end(), name);
    if (it != graph_.uv_maps.end()) return uint32_t(it - graph_.uv_maps.begin());
    if (graph_.uv_maps.size() == VertexTextureData::kSets) {
      warn(where, "more than " + std::to_string(VertexTextureData::kSets) +
                      " UV maps in one material: '" + name + "' is read as '" + graph_.uv_maps[0] +
                      "'");
      return 0;
    }
    graph_.uv_maps.push_back(name);
    return uint32_t(graph_.uv_maps.size() - 1);
  }

  static bool varies_or_nonzero(const ShaderInput& in) {
    return in.kind == ShaderInput::Kind::kTexture || in.value.x != 0.f;
  }

  // Mix and Add shaders must not reach themselves: the host walks the graph at every hit.
  void check_acyclic() const {
    std::vector<int> state(graph_.nodes.size(), 0);  // 0 unseen, 1 on the path, 2 done
    for (size_t i = 0; i < graph_.nodes.size(); ++i)
      visit(uint32_t(i), state);
  }
  void visit(uint32_t i, std::vector<int>& state) const {
    if (state[i] == 2) return;
    if (state[i] == 1)
      throw_input(ext_.file(), ext_.path() + "." + index_path("nodes", i),
                  "the shader nodes form a cycle through this node");
    state[i] = 1;
    for (uint32_t child : graph_.nodes[i].shaders)
      if (child != ShaderNode::kNone) visit(child, state);
    state[i] = 2;
  }

  void warn(const std::string& where, const std::string& what) {
    diagnostics_.warn(located(ext_.file(), where, what));
  }

  const Fields& ext_;
  Scene& scene_;
  Diagnostics& diagnostics_;
  ShaderGraph graph_;
};

}  // namespace

ShaderGraph read_shader_graph(const Fields& extension, Scene& scene, Diagnostics& diagnostics) {
  return GraphReader(extension, scene, diagnostics).read();
}

std::optional<uint32_t> MeshUvMaps::texcoord(const std::string& name) const {
  if (names.empty()) return name.empty() ? std::optional<uint32_t>(0) : std::nullopt;
  const std::string& wanted = name.empty() ? active_render : name;
  const auto it = std::find(names.begin(), names.end(), wanted);
  if (it == names.end()) return std::nullopt;
  return uint32_t(it - names.begin());
}

std::vector<Vec3f> radial_tangents(const std::vector<Vec3f>& positions,
                                   const Fields& mesh_extension) {
  // Blender's axes from glTF's: (x, y, z)_blender = (x, -z, y)_gltf.
  const auto blender = [](Vec3f p) { return Vec3d{p.x, -double(p.z), p.y}; };
  Vec3d location, size;
  const auto loc = mesh_extension.numbers("texspace_location", 3, -kLargestValue, kLargestValue);
  const auto sz = mesh_extension.numbers("texspace_size", 3, -kLargestValue, kLargestValue);
  if (loc && sz && loc->size() == 3 && sz->size() == 3) {
    location = {(*loc)[0], (*loc)[1], (*loc)[2]};
    size = {(*sz)[0], (*sz)[1], (*sz)[2]};
  } else {
    Bounds3d box;
    for (const Vec3f& p : positions)
      box.extend(blender(p));
    if (!box.empty()) location = (box.lo + box.hi) * 0.5, size = (box.hi - box.lo) * 0.5;
  }
  // Cycles' Generated coordinates (blender/mesh.cpp, mesh_texture_space): g = (co - location) /
  // (2 size) + 1/2 per axis, an axis of size 0 left unscaled.
  const auto half_extent = [](double s) { return s != 0 ? 0.5 / s : 1.0; };
  const Vec3d scale{half_extent(size.x), half_extent(size.y), half_extent(size.z)};
  std::vector<Vec3f> out;
  out.reserve(positions.size());
  for (const Vec3f& p : positions) {
    const Vec3d g = (blender(p) - location) * scale;  // g - 1/2
    // svm_node_tangent's radial Z, (-(g.y - 1/2), g.x - 1/2, 0), back in glTF's axes.
    out.push_back(Vec3f(Vec3d{-g.y, 0, -g.x}));
  }
  return out;
}

MeshUvMaps read_mesh_uv_maps(const Fields& mesh_extension) {
  MeshUvMaps maps;
  maps.names = mesh_extension.words("uv_maps", 64).value_or(std::vector<std::string>{});
  maps.active_render = mesh_extension.word("active_render_uv_map").value_or("");
  if (maps.active_render.empty() && !maps.names.empty()) maps.active_render = maps.names[0];
  return maps;
}

}  // namespace fb::gltf
