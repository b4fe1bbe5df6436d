// Blender materials from the add-on's FILMBACK_blender extension (docs/blender.md, "Materials"):
// the shader graph as read, its UV maps found by name on each mesh, errors naming the JSON path,
// and the host's evaluation of the graph at a hit (textures, mix weights, emission, coverage).
#include "importers/gltf/gltf_blender_material.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <fstream>

#include "core/texture/surface_shader.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/png.h"

namespace fb {
namespace {

// A quad whose TEXCOORD_0 runs along x and TEXCOORD_1 along y, the mesh naming them UV maps "A"
// and "B" ("B" the active render one), with one material carrying `graph` as its
// FILMBACK_blender extension, and "tex.png" beside it: two texels, red then green.
std::filesystem::path quad_with(const std::string& graph) {
  const float data[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0,  // POSITION
                        0,  0,  1, 0, 1,  0, 0, 0,               // TEXCOORD_0: u = x
                        0,  0,  0, 0, 1,  0, 1, 0};              // TEXCOORD_1: u = y
  const uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  std::vector<unsigned char> buffer(sizeof data + sizeof indices);
  std::memcpy(buffer.data(), data, sizeof data);
  std::memcpy(buffer.data() + sizeof data, indices, sizeof indices);
  const std::filesystem::path dir = test::scratch_dir();
  const std::vector<unsigned char> texels = test::png(2, 1, {255, 0, 0, 255, 0, 255, 0, 255});
  std::ofstream(dir / "tex.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(texels.data()), std::streamsize(texels.size()));
  const std::filesystem::path file = dir / "quad.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
    "extensionsUsed": ["FILMBACK_blender"], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2},
                                "indices": 3, "material": 0}],
                "extensions": {"FILMBACK_blender": {"uv_maps": ["A", "B"],
                                                     "active_render_uv_map": "B"}}}],
    "materials": [{"name": "Mat", "extensions": {"FILMBACK_blender": )"
                      << graph << R"(}}],
    "buffers": [{"byteLength": )"
                      << buffer.size() << R"(, "uri": "data:application/octet-stream;base64,)"
                      << test::base64(buffer) << R"("}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 112, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [-1, -1, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
  return file;
}

std::string texture(const std::string& fields) {
  return R"({"uri": "tex.png", "extension": "EXTEND", "colorspace": "Non-Color")" +
         (fields.empty() ? "" : ", " + fields) + "}";
}

// Mix(fac 0.25, Principled with textured base colour and roughness from a channel, Emission).
const std::string kMix = R"({"blender_version": [3, 4, 1], "surface": 2, "nodes": [
  {"type": "PRINCIPLED", "name": "Principled BSDF", "distribution": "MULTI_GGX",
   "inputs": {"base_color": {"texture": )" +
                         texture(R"("uv_map": "A")") + R"(},
              "roughness": {"texture": )" +
                         texture(R"("uv_map": "B")") + R"(, "channel": "G"},
              "metallic": 0.25, "specular": 0.5, "sheen_tint": 0.75, "alpha": 1,
              "emission": [0, 0, 0], "emission_strength": 1}},
  {"type": "EMISSION", "name": "Glow", "inputs": {"color": [1, 0.5, 0.25], "strength": 4}},
  {"type": "MIX_SHADER", "name": "Mix", "inputs": {"fac": 0.25}, "shaders": [0, 1]}]})";

struct Imported {
  Scene scene;
  size_t warnings = 0;
};

Imported import(const std::filesystem::path& file) {
  Diagnostics diagnostics;
  Imported out{import_gltf(file, diagnostics), diagnostics.count()};
  return out;
}

std::string import_error(const std::string& graph) {
  try {
    import(quad_with(graph));
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

TEST(BlenderMaterial, GraphKeepsEveryNodeInputAndTexture) {
  const Imported in = import(quad_with(kMix));
  EXPECT_EQ(in.warnings, 0u);
  ASSERT_EQ(in.scene.materials.size(), 1u);
  const Material& m = in.scene.materials[0];
  ASSERT_TRUE(m.shader_graph);
  const ShaderGraph& g = *m.shader_graph;
  ASSERT_EQ(g.nodes.size(), 3u);
  EXPECT_EQ(g.surface, 2u);
  const ShaderNode& principled = g.nodes[0];
  EXPECT_EQ(principled.type, ShaderNodeType::kPrincipled);
  EXPECT_EQ(principled.distribution, Distribution::kMultiGgx);
  EXPECT_EQ(principled.in(Socket::kMetallic).value.x, 0.25f);
  EXPECT_EQ(principled.in(Socket::kSheenTint).value.x, 0.75f);
  // Inputs the file leaves out keep Blender 3.4's defaults.
  EXPECT_EQ(principled.in(Socket::kIor).value.x, 1.45f);
  EXPECT_EQ(principled.in(Socket::kClearcoatRoughness).value.x, 0.03f);
  EXPECT_EQ(principled.in(Socket::kNormal).kind, ShaderInput::Kind::kUnset);
  ASSERT_EQ(principled.in(Socket::kRoughness).kind, ShaderInput::Kind::kTexture);
  EXPECT_EQ(principled.in(Socket::kRoughness).output, TextureOutput::kGreen);
  ASSERT_EQ(g.textures.size(), 2u);
  EXPECT_EQ(g.uv_maps, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(g.textures[0].uv_slot, 0u);
  EXPECT_EQ(g.textures[1].uv_slot, 1u);
  EXPECT_EQ(g.textures[0].wrap, TextureWrap::kClamp);
  EXPECT_FALSE(g.textures[0].srgb);
  // One image file for both textures.
  EXPECT_EQ(g.textures[0].image, g.textures[1].image);
  EXPECT_EQ(in.scene.images[g.textures[0].image].file.filename(), "tex.png");
  EXPECT_EQ(g.nodes[2].shaders, (std::array<uint32_t, 2>{0, 1}));
  // Cycles' emission leaves both faces; the bound for light selection counts the Emission node.
  EXPECT_TRUE(m.double_sided);
  EXPECT_EQ(m.emission.x, 4.f);
  EXPECT_EQ(m.emission.y, 2.f);
  EXPECT_EQ(m.emission.z, 1.f);
  EXPECT_EQ(m.alpha_mode, AlphaMode::kOpaque);
}

TEST(BlenderMaterial, UvMapsAreFoundByNameOnEachMesh) {
  const Imported in = import(quad_with(kMix));
  const TriangleMesh& mesh = in.scene.meshes.at(0);
  // Slot 0 is map "A" (TEXCOORD_0: u = x), slot 1 map "B" (TEXCOORD_1: u = y).
  ASSERT_EQ(mesh.texturing.texcoords[0].size(), 4u);
  ASSERT_EQ(mesh.texturing.texcoords[1].size(), 4u);
  EXPECT_EQ(mesh.texturing.texcoords[0][1].x, 1.f);
  EXPECT_EQ(mesh.texturing.texcoords[1][1].x, 0.f);
  EXPECT_EQ(mesh.texturing.texcoords[1][2].x, 1.f);

  // "" is the mesh's active render map, "B": TEXCOORD_1.
  std::string active = kMix;
  active.replace(active.find(R"("uv_map": "A")"), 13, R"("uv_map": "")");
  const Imported by_default = import(quad_with(active));
  EXPECT_EQ(by_default.scene.meshes[0].texturing.texcoords[0][2].x, 1.f);  // u = y
  EXPECT_EQ(by_default.scene.meshes[0].texturing.texcoords[0][1].x, 0.f);

  // A map the mesh does not have: a warning, and TEXCOORD_0.
  std::string missing = kMix;
  missing.replace(missing.find(R"("uv_map": "A")"), 13, R"("uv_map": "Z")");
  const Imported warned = import(quad_with(missing));
  EXPECT_EQ(warned.warnings, 1u);
  EXPECT_EQ(warned.scene.meshes[0].texturing.texcoords[0][1].x, 1.f);
}

// The graph at a hit: at u = 0.75 on map A the red texel is the base colour, and the roughness is
// the green channel on map B; the mix gives the Emission node a quarter of the weight.
TEST(BlenderMaterial, ShaderEvaluatesTheGraphAtTheHit) {
  const Imported in = import(quad_with(kMix));
  const SurfaceShader shader(in.scene);
  SurfacePoint point;
  point.uv[0] = {0.75f, 0.5f};  // map A: the second texel (green)
  point.uv[1] = {0.25f, 0.5f};  // map B: the first texel (red: green channel 0)
  point.uv_sets = 2;
  fb_hit hit{};
  hit.shading_normal[2] = 1.f;
  shader.shade(0, point, hit);
  EXPECT_EQ(hit.base_color[0], 0.f);
  EXPECT_EQ(hit.base_color[1], 1.f);  // Non-Color: not decoded
  EXPECT_EQ(hit.roughness, 0.f);
  EXPECT_EQ(hit.metallic, 0.25f);
  EXPECT_NEAR(hit.emission[0], 0.25f * 4.f, 1e-6);
  EXPECT_NEAR(hit.emission[1], 0.25f * 2.f, 1e-6);
  EXPECT_EQ(shader.alpha(0, point), 1.f);
}

// Transparency: a Transparent node mixed in at 0.4 leaves coverage 0.6, and what the kept hits
// emit is divided by it, so that coverage times emission is the mix's emission.
TEST(BlenderMaterial, TransparentWeightBecomesCoverage) {
  const std::string graph = R"({"surface": 2, "nodes": [
    {"type": "TRANSPARENT", "inputs": {"color": [1, 1, 1]}},
    {"type": "EMISSION", "inputs": {"color": [1, 1, 1], "strength": 2}},
    {"type": "MIX_SHADER", "inputs": {"fac": 0.6}, "shaders": [0, 1]}]})";
  const Imported in = import(quad_with(graph));
  EXPECT_EQ(in.scene.materials[0].alpha_mode, AlphaMode::kBlend);
  const SurfaceShader shader(in.scene);
  const SurfacePoint point;
  EXPECT_NEAR(shader.alpha(0, point), 0.6f, 1e-6);
  EXPECT_NEAR(shader.emission(0, point).x * shader.alpha(0, point), 0.6f * 2.f, 1e-6);
}

// Subsurface scattering is rendered as its diffuse fallback: said once per node that has it.
TEST(BlenderMaterial, SubsurfaceIsWarnedAsAFallback) {
  const Imported none = import(quad_with(R"({"surface": 0, "nodes": [
    {"type": "PRINCIPLED", "inputs": {"subsurface": 0}}]})"));
  EXPECT_EQ(none.warnings, 0u);
  const Imported some = import(quad_with(R"({"surface": 0, "nodes": [
    {"type": "PRINCIPLED", "name": "Skin", "inputs": {"subsurface": 0.3}}]})"));
  EXPECT_EQ(some.warnings, 1u);
}

TEST(BlenderMaterial, BadGraphsNameTheJsonPath) {
  const std::string at = "quad.gltf: materials[0].extensions.FILMBACK_blender.";
  const auto expect = [](const std::string& error, const std::string& wanted) {
    EXPECT_NE(error.find(wanted), std::string::npos) << error;
  };
  expect(import_error(R"({"nodes": [{"type": "TOON"}]})"),
         at + "nodes[0].type: 'TOON' is not a node type");
  expect(import_error(R"({"nodes": [{"type": "DIFFUSE", "inputs": {"metallic": 1}}]})"),
         at + "nodes[0].inputs.metallic: a DIFFUSE node has no such input");
  expect(import_error(R"({"nodes": [{"type": "DIFFUSE", "inputs": {"color": 1}}]})"),
         at + "nodes[0].inputs.color: expected [r, g, b] or a texture");
  expect(import_error(R"({"nodes": [{"type": "GLASS", "distribution": "ASHIKHMIN_SHIRLEY"}]})"),
         at + "nodes[0].distribution: 'ASHIKHMIN_SHIRLEY' is not a distribution of this node");
  expect(import_error(R"({"surface": 0, "nodes": [
           {"type": "ADD_SHADER", "shaders": [1, -1]},
           {"type": "MIX_SHADER", "shaders": [0, -1]}]})"),
         "the shader nodes form a cycle through this node");
  expect(import_error(R"({"nodes": [{"type": "ADD_SHADER", "shaders": [5, -1]}]})"),
         at + "nodes[0].shaders[0]: expected -1 (none) or an index below 1");
  expect(
      import_error(
          R"({"nodes": [{"type": "DIFFUSE", "inputs": {"color": {"texture": {"uri": "../x.png"}}}}]})"),
      at + "nodes[0].inputs.color.texture.uri: '../x.png' refers outside the scene's folder");
  expect(import_error(R"({"surface": 3, "nodes": []})"), at + "surface");
}

}  // namespace
}  // namespace fb

namespace fb {
namespace {

// Cycles' default tangent (radial about Blender's Z, through the texture space's centre), per
// vertex in glTF's object axes: at Blender (1, 0, 0), 1 m right of a centre with half-size 2, the
// Generated coordinate is 1/2 + 1/4 and the radial direction Blender's (0, 1/4, 0), which is
// glTF's (0, 0, -1/4); at Blender (0, 2, 0) it is Blender's (-1/2, 0, 0).
TEST(BlenderMaterial, RadialTangentsFollowBlendersTextureSpace) {
  tinygltf::Value::Object ext;
  ext["texspace_location"] = gltf::number_array({0.0, 0.0, 0.0});
  ext["texspace_size"] = gltf::number_array({2.0, 2.0, 2.0});
  const tinygltf::Value value(ext);
  const gltf::Fields fields(value, "meshes[0].extensions.FILMBACK_blender", "x.gltf");
  // glTF (x, y, z) is Blender (x, -z, y).
  const std::vector<Vec3f> t = gltf::radial_tangents({{1, 0, 0}, {0, 0, -2}}, fields);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].x, 0.f);
  EXPECT_EQ(t[0].y, 0.f);
  EXPECT_EQ(t[0].z, -0.25f);
  EXPECT_EQ(t[1].x, -0.5f);
  EXPECT_EQ(t[1].y, 0.f);
  EXPECT_EQ(t[1].z, 0.f);
  // Without a texture space, the positions' bounds (Blender's automatic one): centre (1/2, 1, 0),
  // half-size (1/2, 1, 0); the flat z axis stays unscaled.
  const tinygltf::Value none;
  const std::vector<Vec3f> a =
      gltf::radial_tangents({{1, 0, 0}, {0, 0, -2}}, gltf::Fields(none, "m", "x.gltf"));
  EXPECT_EQ(a[0].z, -0.5f);  // Blender x: (1 - 1/2) / (2 * 1/2)
  EXPECT_EQ(a[0].x, 0.5f);   // Blender y: -(0 - 1) / (2 * 1)
}

}  // namespace
}  // namespace fb
