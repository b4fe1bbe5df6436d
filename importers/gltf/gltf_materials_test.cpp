// Materials: the glTF reader's checks and conversions (on tinygltf models built here), texture
// lookups through the host's SurfaceShader (sRGB decoding, KHR_texture_transform, wrap modes),
// and alpha coverage as Embree sees it (MASK drops hits, BLEND keeps a share of alpha).
#include "importers/gltf/gltf_materials.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>

#include "core/accel/render_geometry.h"
#include "core/texture/surface_shader.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"
#include "support/png.h"

namespace fb {
namespace {

using test::base64;
using test::png;

// The message of the InputError that reading `model`'s materials throws, or "" if none.
std::string material_error(tinygltf::Model model) {
  Scene scene;
  Diagnostics diagnostics;
  try {
    gltf::read_materials(model, "scene.gltf", scene, diagnostics);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

tinygltf::Model one_material(const tinygltf::Material& m) {
  tinygltf::Model model;
  model.materials.push_back(m);
  model.images.emplace_back();
  model.images.back().image = {
      0x89};  // encoded bytes, as the loader keeps them; never decoded here
  tinygltf::Texture texture;
  texture.source = 0;
  model.textures.push_back(texture);
  return model;
}

TEST(GltfMaterials, BadValuesNameTheFileAndTheJsonPath) {
  tinygltf::Material rough;
  rough.pbrMetallicRoughness.roughnessFactor = 1.5;
  EXPECT_NE(material_error(one_material(rough))
                .find("scene.gltf: materials[0].pbrMetallicRoughness.roughnessFactor: 1.5"),
            std::string::npos);

  tinygltf::Material texture;
  texture.pbrMetallicRoughness.baseColorTexture.index = 3;
  EXPECT_NE(material_error(one_material(texture))
                .find("materials[0].pbrMetallicRoughness.baseColorTexture.index: texture index 3 "
                      "is out of range (the file has 1 textures)"),
            std::string::npos);

  tinygltf::Material set;
  set.normalTexture.index = 0;
  set.normalTexture.texCoord = 2;
  EXPECT_NE(material_error(one_material(set)).find("materials[0].normalTexture.texCoord"),
            std::string::npos);

  tinygltf::Material ior;
  tinygltf::Value::Object e;
  e["ior"] = tinygltf::Value(0.5);
  ior.extensions["KHR_materials_ior"] = tinygltf::Value(e);
  EXPECT_NE(material_error(one_material(ior))
                .find("scene.gltf: materials[0].extensions.KHR_materials_ior.ior: expected a "
                      "number in [1, 10]"),
            std::string::npos);

  tinygltf::Material mode;
  mode.alphaMode = "CUTOUT";
  EXPECT_NE(material_error(one_material(mode)).find("materials[0].alphaMode: 'CUTOUT'"),
            std::string::npos);

  tinygltf::Material transform;
  transform.emissiveTexture.index = 0;
  tinygltf::Value::Object t;
  t["scale"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(1.0)});
  transform.emissiveTexture.extensions["KHR_texture_transform"] = tinygltf::Value(t);
  EXPECT_NE(material_error(one_material(transform))
                .find("materials[0].emissiveTexture.extensions.KHR_texture_transform.scale: "
                      "expected two finite numbers"),
            std::string::npos);
}

TEST(GltfMaterials, FactorsAndExtensionsAreCarried) {
  tinygltf::Material g;
  g.pbrMetallicRoughness.baseColorFactor = {0.5, 0.25, 1, 0.75};
  g.pbrMetallicRoughness.metallicFactor = 0.3;
  g.pbrMetallicRoughness.roughnessFactor = 0.2;
  g.alphaMode = "MASK";
  g.alphaCutoff = 0.4;
  tinygltf::Value::Object transmission, ior;
  transmission["transmissionFactor"] = tinygltf::Value(0.9);
  ior["ior"] = tinygltf::Value(1.33);
  g.extensions["KHR_materials_transmission"] = tinygltf::Value(transmission);
  g.extensions["KHR_materials_ior"] = tinygltf::Value(ior);
  g.pbrMetallicRoughness.baseColorTexture.index = 0;
  g.pbrMetallicRoughness.baseColorTexture.texCoord = 1;
  tinygltf::Value::Object t;
  t["offset"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(0.5), tinygltf::Value(0.0)});
  t["rotation"] = tinygltf::Value(std::numbers::pi / 2);
  t["scale"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(2.0), tinygltf::Value(3.0)});
  g.pbrMetallicRoughness.baseColorTexture.extensions["KHR_texture_transform"] = tinygltf::Value(t);
  tinygltf::Model model = one_material(g);
  Scene scene;
  Diagnostics diagnostics;
  gltf::read_materials(model, "scene.gltf", scene, diagnostics);
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_FLOAT_EQ(m.base_color.y, 0.25f);
  EXPECT_FLOAT_EQ(m.alpha, 0.75f);
  EXPECT_FLOAT_EQ(m.metallic, 0.3f);
  EXPECT_FLOAT_EQ(m.roughness, 0.2f);
  EXPECT_FLOAT_EQ(m.transmission, 0.9f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_EQ(m.alpha_mode, AlphaMode::kMask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.4f);
  EXPECT_EQ(m.textures.base_color.texcoord, 1u);
  // T(0.5, 0) R(pi/2) S(2, 3) with R = [c s; -s c]: u' = 3 v + 0.5, v' = -2 u.
  const auto& x = m.textures.base_color.uv_transform;
  const std::array<float, 6> expected{0, 3, 0.5f, -2, 0, 0};
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(x[i], expected[i], 1e-6) << i;
  EXPECT_EQ(diagnostics.count(), 0u);
}

// Blender writes Principled's Specular s as KHR_materials_ior 1.45 and a grey specularColorFactor
// with F0 = 0.08 s; an opaque material carries it as the index giving that F0.
TEST(GltfMaterials, SpecularColourFoldsIntoTheIndexOfAnOpaqueMaterial) {
  for (double s : {0.0, 0.25, 1.0}) {
    tinygltf::Material g;
    tinygltf::Value::Object ior, specular;
    ior["ior"] = tinygltf::Value(1.45);
    const double f0_ior = std::pow(0.45 / 2.45, 2);
    const tinygltf::Value c(0.08 * s / f0_ior);
    specular["specularColorFactor"] = tinygltf::Value(tinygltf::Value::Array{c, c, c});
    g.extensions["KHR_materials_ior"] = tinygltf::Value(ior);
    g.extensions["KHR_materials_specular"] = tinygltf::Value(specular);
    tinygltf::Model model = one_material(g);
    Scene scene;
    Diagnostics diagnostics;
    gltf::read_materials(model, "scene.gltf", scene, diagnostics);
    const double eta = scene.materials[0].ior;
    EXPECT_NEAR(std::pow((eta - 1) / (eta + 1), 2), 0.08 * s, 1e-6) << "Specular " << s;
    EXPECT_EQ(diagnostics.count(), 0u);
  }
}

// Two texels: left (64, 128, 255) half transparent, right (255, 0, 0) opaque.
std::vector<unsigned char> two_texels() {
  return png(2, 1, {64, 128, 255, 128, 255, 0, 0, 255});
}

SurfacePoint at_uv(float u, float v) {
  SurfacePoint p;
  p.uv[0] = {u, v};
  p.uv_sets = 1;
  return p;
}

TEST(SurfaceShader, BaseColourTextureIsDecodedFromSrgbAndMultipliedByTheFactor) {
  Scene scene;
  scene.images.push_back({"images[0]", {}, two_texels()});
  Material m;
  m.base_color = {0.5f, 1.f, 1.f};
  m.textures.base_color.image = 0;
  m.textures.base_color.wrap_s = TextureWrap::kClamp;
  scene.materials.push_back(m);
  const SurfaceShader shader(scene);
  fb_hit hit{};
  hit.shading_normal[2] = 1;
  shader.shade(0, at_uv(0.25f, 0.5f), hit);  // the left texel's centre
  EXPECT_NEAR(hit.base_color[0], 0.5f * srgb_to_linear(64 / 255.f), 1e-4);
  EXPECT_NEAR(hit.base_color[1], srgb_to_linear(128 / 255.f), 1e-4);
  EXPECT_NEAR(hit.base_color[2], 1.f, 1e-4);
  EXPECT_NEAR(shader.alpha(0, at_uv(0.25f, 0.5f)), 128 / 255.f, 1e-3);
  // Known sRGB values (IEC 61966-2-1): 128 -> 0.2158605.
  EXPECT_NEAR(srgb_to_linear(128 / 255.f), 0.2158605f, 1e-6);
}

TEST(SurfaceShader, TextureTransformMovesTheLookup) {
  Scene scene;
  scene.images.push_back({"images[0]", {}, two_texels()});
  Material m;
  m.textures.base_color.image = 0;
  m.textures.base_color.uv_transform = {1, 0, 0.5f, 0, 1, 0};  // offset u by half the image
  scene.materials.push_back(m);
  const SurfaceShader shader(scene);
  fb_hit hit{};
  shader.shade(0, at_uv(0.25f, 0.5f), hit);  // lands on the right texel
  EXPECT_NEAR(hit.base_color[0], 1.f, 1e-4);
  EXPECT_NEAR(hit.base_color[1], 0.f, 1e-4);
  // Repeat wrap: u = 0.75 + 0.5 wraps to the left texel.
  shader.shade(0, at_uv(0.75f, 0.5f), hit);
  EXPECT_NEAR(hit.base_color[1], srgb_to_linear(128 / 255.f), 1e-4);
}

// glTF 2.0 §3.9.3: n = normalize(T x + B y + N z) with (x, y, z) = (2 rgb - 1) (scale, scale, 1)
// and B = w (N x T); the texture is linear, not sRGB.
TEST(SurfaceShader, NormalMapTiltsTheShadingNormalInTheTangentFrame) {
  Scene scene;
  scene.images.push_back({"images[0]", {}, png(1, 1, {191, 64, 221, 255})});
  Material m;
  m.textures.normal.image = 0;
  m.textures.normal_scale = 0.5f;
  scene.materials.push_back(m);
  const SurfaceShader shader(scene);
  for (float w : {1.f, -1.f}) {
    SurfacePoint point = at_uv(0.5f, 0.5f);
    point.tangent = {0, 0, -1};  // in the plane of the normal below
    point.bitangent_sign = w;
    fb_hit hit{};
    hit.shading_normal[0] = 1;  // N = +x, T = -z, N x T = +y
    shader.shade(0, point, hit);
    const double x = (2 * 191 / 255.0 - 1) * 0.5, y = (2 * 64 / 255.0 - 1) * 0.5;
    const double z = 2 * 221 / 255.0 - 1;
    const double len = std::sqrt(x * x + y * y + z * z);
    EXPECT_NEAR(hit.shading_normal[0], z / len, 1e-4) << "w " << w;      // along N
    EXPECT_NEAR(hit.shading_normal[1], w * y / len, 1e-4) << "w " << w;  // along B
    EXPECT_NEAR(hit.shading_normal[2], -x / len, 1e-4) << "w " << w;     // along T
  }
}

TEST(SurfaceShader, UnreadableEmbeddedImageIsAnErrorNamingIt) {
  Scene scene;
  scene.file = "shot.gltf";
  scene.images.push_back({"images[0]", {}, {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'g'}});
  Material m;
  m.textures.emissive.image = 0;
  scene.materials.push_back(m);
  try {
    const SurfaceShader shader(scene);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shot.gltf: images[0]"), std::string::npos) << e.what();
  }
}

// A unit quad at z = -1 with u across x, as a glTF exporter writes it.
Scene quad_scene(const Material& material, std::vector<unsigned char> image) {
  Scene scene;
  TriangleMesh mesh;
  mesh.positions = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.texturing.texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, Transform(), "quad"});
  scene.materials.push_back(material);
  if (!image.empty()) scene.images.push_back({"images[0]", {}, std::move(image)});
  return scene;
}

fb_ray ray_towards(float x, float y, float dx = 0, float dy = 0) {
  fb_ray ray{};
  ray.origin[0] = x, ray.origin[1] = y;
  ray.direction[0] = dx, ray.direction[1] = dy, ray.direction[2] = -1;
  ray.t_max = HUGE_VALF;
  return ray;
}

TEST(AlphaCoverage, MaskDropsHitsWhereTheTextureAlphaIsBelowTheCutoff) {
  Material m;
  m.alpha_mode = AlphaMode::kMask;
  m.alpha_cutoff = 0.6f;  // above the left texel's 0.5
  m.textures.base_color.image = 0;
  m.textures.base_color.wrap_s = TextureWrap::kClamp;
  const Scene scene = quad_scene(m, two_texels());
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  fb_hit hit;
  EXPECT_FALSE(geometry.intersect(ray_towards(-0.5f, 0), hit));
  EXPECT_FALSE(geometry.occluded(ray_towards(-0.5f, 0)));
  EXPECT_TRUE(geometry.intersect(ray_towards(0.5f, 0), hit));
  EXPECT_TRUE(geometry.occluded(ray_towards(0.5f, 0)));
}

TEST(AlphaCoverage, BlendKeepsAShareOfHitsEqualToAlpha) {
  Material m;
  m.alpha_mode = AlphaMode::kBlend;
  m.alpha = 0.25f;
  const Scene scene = quad_scene(m, {});
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  int hits = 0;
  constexpr int kN = 20000;
  for (int i = 0; i < kN; ++i) {
    const float x = -0.9f + 1.8f * float(i % 200) / 200, y = -0.9f + 1.8f * float(i / 200) / 100;
    fb_hit hit;
    hits += geometry.intersect(ray_towards(x, y, 0.01f * float(i % 7), 0.01f * float(i % 5)), hit);
  }
  // Binomial standard deviation sqrt(0.25 * 0.75 / 20000) = 0.003: five of them.
  EXPECT_NEAR(double(hits) / kN, 0.25, 0.015);
}

}  // namespace
}  // namespace fb

namespace fb {
namespace {

// A textured quad written by hand: positions, TEXCOORD_0 and indices in a data-URI buffer, the
// image `image_uri`, the base colour texture reading TEXCOORD_n for n = `texcoord`.
std::filesystem::path textured_quad(const std::string& image_uri, int texcoord = 0) {
  const float data[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0,  // POSITION
                        0,  1,  1, 1, 1,  0, 0, 0};              // TEXCOORD_0
  const uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  std::vector<unsigned char> buffer(sizeof data + sizeof indices);
  std::memcpy(buffer.data(), data, sizeof data);
  std::memcpy(buffer.data() + sizeof data, indices, sizeof indices);
  const std::filesystem::path file = test::scratch_dir() / "quad.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                "material": 0}]}],
    "materials": [{"pbrMetallicRoughness": {"metallicFactor": 0,
                   "baseColorTexture": {"index": 0, "texCoord": )"
                      << texcoord << R"(}}}],
    "textures": [{"source": 0}], "images": [{"uri": ")"
                      << image_uri << R"("}],
    "buffers": [{"byteLength": )"
                      << buffer.size() << R"(, "uri": "data:application/octet-stream;base64,)"
                      << base64(buffer) << R"("}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [-1, -1, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
  return file;
}

// The whole way from a .gltf: a data-URI PNG kept encoded by the importer, TEXCOORD_0 read, the
// image decoded by the shader and looked up where the quad's corner maps.
TEST(GltfMaterials, DataUriImageAndTexcoordsReachTheShader) {
  const std::string uri = "data:image/png;base64," + base64(two_texels());
  Diagnostics diagnostics;
  const Scene scene = import_gltf(textured_quad(uri), diagnostics);
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.meshes[0].texturing.texcoords[0].size(), 4u);
  EXPECT_EQ(diagnostics.count(), 0u);
  const SurfaceShader shader(scene);
  fb_hit hit{};
  shader.shade(0, at_uv(0.75f, 0.5f), hit);  // the right texel: (255, 0, 0)
  EXPECT_NEAR(hit.base_color[0], 1.f, 1e-4);
  EXPECT_NEAR(hit.base_color[1], 0.f, 1e-4);
}

TEST(GltfMaterials, ImagesOutsideTheScenesFolderAndMissingTexcoordsAreErrors) {
  const std::string outside = test::import_error(textured_quad("../outside.png"));
  EXPECT_NE(outside.find("quad.gltf: images[0].uri: '../outside.png' refers outside the scene's "
                         "folder"),
            std::string::npos)
      << outside;
  const std::string uri = "data:image/png;base64," + base64(two_texels());
  const std::string missing = test::import_error(textured_quad(uri, 1));
  EXPECT_NE(missing.find("quad.gltf: meshes[0].primitives[0].attributes: material 'materials[0]' "
                         "reads TEXCOORD_1, which the primitive does not have"),
            std::string::npos)
      << missing;
}

}  // namespace
}  // namespace fb
