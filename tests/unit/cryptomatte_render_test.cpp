// Cryptomatte (--passes CryptoObject,CryptoMaterial; core/film/cryptomatte.h) decoded from a
// render whose silhouettes are known: two quads side by side, their common edge through the middle
// of a pixel column and the right one's far edge a quarter into another.
#include <gtest/gtest.h>

#include <filmback/render_passes.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/film/cryptomatte.h"
#include "core/render/render_job.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"
#include "support/plugins.h"

namespace fb {
namespace {

// A pinhole at the origin looking down -z, 35 mm lens on a 36 mm sensor, 40 x 40 pixels; the quads
// stand 2 m away, so that a pixel is 2 m x 0.9 mm / 35 mm wide there.
constexpr uint32_t kCryptoImagePx = 40;
constexpr double kCryptoDistanceM = 2, kCryptoFocalMm = 35, kCryptoSensorMm = 36;
constexpr double kCryptoPixelM =
    kCryptoDistanceM * kCryptoSensorMm / kCryptoImagePx / kCryptoFocalMm;
// In pixels from the image's left edge: where Left gives way to Right (the middle of column 20),
// and where Right ends (a quarter into column 30).
constexpr double kCryptoSeamPx = 20.5, kCryptoRightEndPx = 30.25;

double crypto_world_x(double px) {
  return (px - kCryptoImagePx / 2.0) * kCryptoPixelM;
}

// A rectangle from x0 to x1 across the whole height of the view, facing the camera.
TriangleMesh crypto_quad(double x0, double x1, uint32_t material) {
  const float y = float(kCryptoImagePx * kCryptoPixelM), z = float(-kCryptoDistanceM);
  TriangleMesh mesh;
  mesh.name = "quad";
  mesh.positions = {{float(x0), -y, z}, {float(x1), -y, z}, {float(x1), y, z}, {float(x0), y, z}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.material = material;
  return mesh;
}

Scene crypto_scene() {
  Scene scene;
  for (const char* name : {"RedMat", "BlueMat"}) {
    Material m;
    m.name = name;
    scene.materials.push_back(m);
  }
  scene.meshes = {crypto_quad(crypto_world_x(-10), crypto_world_x(kCryptoSeamPx), 0),
                  crypto_quad(crypto_world_x(kCryptoSeamPx), crypto_world_x(kCryptoRightEndPx), 1)};
  scene.instances = {{0, Transform(), "Left"}, {1, Transform(), "Right"}};
  SceneCamera camera;
  camera.name = "camera";
  camera.physical.focal_length_mm = kCryptoFocalMm;
  camera.physical.sensor_width_mm = kCryptoSensorMm;
  scene.cameras.push_back(camera);
  scene.background = {0.5f, 0.5f, 0.5f};
  return scene;
}

RenderOptions crypto_options(std::vector<std::string> passes) {
  RenderOptions options;
  options.width = options.height = kCryptoImagePx;
  options.samples_per_pixel = 64;
  options.filter = "box";  // a pixel's coverage is the share of its area
  options.show_progress = false;
  options.passes = std::move(passes);
  return options;
}

// Per pixel of `image`, each name's coverage in the Cryptomatte pass `pass`, the names found
// through the manifest of `metadata` (as Blender's Cryptomatte node reads them), from its
// levels / 2 RGBA layers.
std::vector<std::map<std::string, float>> decode(
    const Image& image, const std::vector<std::pair<std::string, std::string>>& metadata,
    const std::string& pass, uint32_t levels = kDefaultCryptomatteLevels) {
  std::map<uint32_t, std::string> name_of_id;
  const std::string key =
      "cryptomatte/" + cryptomatte_hex(cryptomatte_hash("ViewLayer." + pass)).substr(0, 7);
  nlohmann::json manifest;
  for (const auto& [k, value] : metadata)
    if (k == key + "/manifest") manifest = nlohmann::json::parse(value);
  for (const auto& [name, hex] : manifest.items())
    name_of_id[std::bit_cast<uint32_t>(
        cryptomatte_id(uint32_t(std::stoul(hex.get<std::string>(), nullptr, 16))))] = name;
  EXPECT_FALSE(name_of_id.empty()) << key;
  std::vector<std::map<std::string, float>> coverage(size_t(image.width) * image.height);
  for (uint32_t rgba = 0; rgba < levels / 2; ++rgba) {
    const std::string layer =
        "ViewLayer." + pass + (rgba < 10 ? "0" : "") + std::to_string(rgba) + ".";
    const auto first = std::find(image.channels.begin(), image.channels.end(), layer + "r");
    EXPECT_NE(first, image.channels.end()) << layer;
    if (first == image.channels.end()) break;
    const size_t r = size_t(first - image.channels.begin());
    for (uint32_t y = 0; y < image.height; ++y)
      for (uint32_t x = 0; x < image.width; ++x)
        for (size_t pair = 0; pair < 2; ++pair) {
          const float weight = image.at(x, y, r + 2 * pair + 1);
          if (weight == 0.f) continue;
          const uint32_t id = std::bit_cast<uint32_t>(image.at(x, y, r + 2 * pair));
          EXPECT_TRUE(name_of_id.count(id)) << x << "," << y;
          coverage[size_t(y) * image.width + x][name_of_id[id]] += weight;
        }
  }
  return coverage;
}

// What share of pixel column `x` lies in [x0, x1) (pixels).
double column_share(uint32_t x, double x0, double x1) {
  return std::clamp(std::min(x1, x + 1.0) - std::max(x0, double(x)), 0.0, 1.0);
}

TEST(CryptomatteRender, ObjectAndMaterialCoverageIsEachQuadsShareOfThePixel) {
  const Scene scene = crypto_scene();  // the job keeps a reference to it
  const RenderJob job(scene, crypto_options({"CryptoObject", "CryptoMaterial"}), test::loader());
  const RenderResult result = job.run();
  const auto objects = decode(result.image, result.cryptomatte_metadata, "CryptoObject");
  const auto materials = decode(result.image, result.cryptomatte_metadata, "CryptoMaterial");
  // 64 samples: a half-covered pixel's share has a standard deviation of 1/16 at worst (random
  // positions); stratified ones do better.
  constexpr float kShareTolerance = 0.13f;
  for (uint32_t y = 0; y < kCryptoImagePx; ++y)
    for (uint32_t x = 0; x < kCryptoImagePx; ++x) {
      const auto& o = objects[size_t(y) * kCryptoImagePx + x];
      const auto& m = materials[size_t(y) * kCryptoImagePx + x];
      const double left = column_share(x, 0, kCryptoSeamPx);
      const double right = column_share(x, kCryptoSeamPx, kCryptoRightEndPx);
      const auto share = [](const std::map<std::string, float>& c, const char* name) {
        const auto it = c.find(name);
        return it == c.end() ? 0.f : it->second;
      };
      EXPECT_NEAR(share(o, "Left"), left, left == 0 || left == 1 ? 0 : kShareTolerance)
          << x << "," << y;
      EXPECT_NEAR(share(o, "Right"), right, right == 0 || right == 1 ? 0 : kShareTolerance)
          << x << "," << y;
      EXPECT_LE(o.size(), 2u);
      // The materials follow their objects exactly: the same samples.
      EXPECT_EQ(share(m, "RedMat"), share(o, "Left")) << x << "," << y;
      EXPECT_EQ(share(m, "BlueMat"), share(o, "Right")) << x << "," << y;
      // Covered by the quads, the coverage sums to 1 (up to float rounding).
      float sum = 0;
      for (const auto& [name, c] : o)
        sum += c;
      if (left + right == 1) {
        EXPECT_NEAR(sum, 1.f, 1e-5f) << x << "," << y;
      }
    }
}

TEST(CryptomatteRender, LeavesTheBeautyAndTheOtherPassesAsTheyWere) {
  const Scene scene = crypto_scene();
  const Image with =
      RenderJob(scene, crypto_options({"Depth", "CryptoObject"}), test::loader()).run().image;
  const Image without = RenderJob(scene, crypto_options({"Depth"}), test::loader()).run().image;
  ASSERT_EQ(with.channels.size(), without.channels.size() + 12);
  for (uint32_t y = 0; y < kCryptoImagePx; ++y)
    for (uint32_t x = 0; x < kCryptoImagePx; ++x)
      for (size_t c = 0; c < without.channels.size(); ++c) {
        ASSERT_EQ(with.channels[c], without.channels[c]);
        ASSERT_EQ(std::bit_cast<uint32_t>(with.at(x, y, c)),
                  std::bit_cast<uint32_t>(without.at(x, y, c)))
            << with.channels[c] << " " << x << "," << y;
      }
}

TEST(CryptomatteRender, InstancesOfOneMeshAndSolidsKeepTheirOwnNames) {
  // One mesh placed twice (an Embree instance each: Instancing::kRepeated), and a ball (a solid)
  // 1.5 m away in the middle, about 5 pixels across.
  Scene scene = crypto_scene();
  const double shift_m = crypto_world_x(kCryptoSeamPx) - crypto_world_x(-10);
  scene.meshes.pop_back();
  scene.instances[1] = {0, Transform::translate({shift_m, 0, 0}), "Right"};
  Material ball_material;
  ball_material.name = "BallMat";
  scene.materials.push_back(ball_material);
  Solid ball;
  ball.kind = SolidKind::kSphere;
  ball.name = "Ball";
  ball.material = 2;
  ball.world_from_object = Transform::translate({0, 0, -1.5}) * Transform::scale({0.1, 0.1, 0.1});
  scene.solids.push_back(ball);
  const RenderResult result =
      RenderJob(scene, crypto_options({"CryptoObject", "CryptoMaterial"}), test::loader()).run();
  const auto objects = decode(result.image, result.cryptomatte_metadata, "CryptoObject");
  const auto materials = decode(result.image, result.cryptomatte_metadata, "CryptoMaterial");
  const auto at = [](const std::vector<std::map<std::string, float>>& c, uint32_t x, uint32_t y) {
    return c[size_t(y) * kCryptoImagePx + x];
  };
  using Coverage = std::map<std::string, float>;
  EXPECT_EQ(at(objects, 5, 5), (Coverage{{"Left", 1.f}}));
  EXPECT_EQ(at(objects, 35, 5), (Coverage{{"Right", 1.f}}));
  EXPECT_EQ(at(materials, 5, 5), (Coverage{{"RedMat", 1.f}}));  // one mesh: one material
  EXPECT_EQ(at(materials, 35, 5), (Coverage{{"RedMat", 1.f}}));
  for (const uint32_t x : {19u, 20u})
    for (const uint32_t y : {19u, 20u}) {
      EXPECT_EQ(at(objects, x, y), (Coverage{{"Ball", 1.f}})) << x << "," << y;
      EXPECT_EQ(at(materials, x, y), (Coverage{{"BallMat", 1.f}})) << x << "," << y;
    }
}

TEST(CryptomatteRender, AssetsNameEachObjectByItsTopmostParent) {
  // A glTF file: "Parent" with children "ChildA" and "ChildB", and a lone "Lone", four quads side
  // by side across columns [-10, 10), [10, 20), [20, 30) and [30, 50), seen by the same pinhole.
  test::GltfBuilder gltf;
  const int material = gltf.material({0.5f, 0.5f, 0.5f});
  const auto quad = [&](double x0, double x1) {
    const TriangleMesh m = crypto_quad(crypto_world_x(x0), crypto_world_x(x1), 0);
    return gltf.mesh(m.positions, m.indices, material);
  };
  test::GltfBuilder::Node child_a, child_b, parent, lone, camera;
  child_a.name = "ChildA", child_a.mesh = quad(10, 20);
  child_b.name = "ChildB", child_b.mesh = quad(20, 30);
  parent.name = "Parent", parent.mesh = quad(-10, 10);
  parent.children = {gltf.node(child_a, false), gltf.node(child_b, false)};
  gltf.node(parent);
  lone.name = "Lone", lone.mesh = quad(30, 50);
  gltf.node(lone);
  camera.name = "Camera";
  camera.camera =
      gltf.perspective_camera(2 * std::atan(kCryptoSensorMm / 2 / kCryptoFocalMm), 1.0, 0.1, 100.0);
  gltf.node(camera);
  const Scene scene = test::import_built(gltf, "assets.gltf");
  const RenderResult result =
      RenderJob(scene, crypto_options({"CryptoObject", "CryptoAsset"}), test::loader()).run();
  const auto objects = decode(result.image, result.cryptomatte_metadata, "CryptoObject");
  const auto assets = decode(result.image, result.cryptomatte_metadata, "CryptoAsset");
  using Coverage = std::map<std::string, float>;
  const struct {
    uint32_t x;
    const char *object, *asset;
  } columns[] = {{5, "Parent", "Parent"},
                 {15, "ChildA", "Parent"},
                 {25, "ChildB", "Parent"},
                 {35, "Lone", "Lone"}};
  for (const auto& c : columns)
    for (const uint32_t y : {2u, 20u, 37u}) {
      const size_t pixel = size_t(y) * kCryptoImagePx + c.x;
      EXPECT_EQ(objects[pixel], (Coverage{{c.object, 1.f}})) << c.x << "," << y;
      EXPECT_EQ(assets[pixel], (Coverage{{c.asset, 1.f}})) << c.x << "," << y;
    }
  // Across the seam between ChildA and ChildB (the middle of column 20) one asset covers it all.
  EXPECT_EQ(assets[20 * kCryptoImagePx + 20], (Coverage{{"Parent", 1.f}}));
  // The manifest lists the assets met, the camera's root not among them.
  const std::string key =
      "cryptomatte/" + cryptomatte_hex(cryptomatte_hash("ViewLayer.CryptoAsset")).substr(0, 7);
  const std::map<std::string, std::string> metadata(result.cryptomatte_metadata.begin(),
                                                    result.cryptomatte_metadata.end());
  EXPECT_EQ(nlohmann::json::parse(metadata.at(key + "/manifest")),
            (nlohmann::json{{"Lone", cryptomatte_hex(cryptomatte_hash("Lone"))},
                            {"Parent", cryptomatte_hex(cryptomatte_hash("Parent"))}}));
}

TEST(CryptomatteRender, LevelsSetTheRgbaLayersWritten) {
  // Blender's Levels: levels / 2 RGBA layers, each decoded as at the default 6.
  const Scene scene = crypto_scene();
  for (const uint32_t levels : {2u, 10u}) {
    RenderOptions options = crypto_options({"CryptoObject"});
    options.cryptomatte_levels = levels;
    const RenderResult result = RenderJob(scene, options, test::loader()).run();
    const auto crypto_channels =
        std::count_if(result.image.channels.begin(), result.image.channels.end(),
                      [](const std::string& c) { return c.starts_with("ViewLayer.CryptoObject"); });
    EXPECT_EQ(crypto_channels, levels / 2 * 4) << levels;
    const std::string last = "ViewLayer.CryptoObject0" + std::to_string(levels / 2 - 1) + ".a";
    EXPECT_NE(std::find(result.image.channels.begin(), result.image.channels.end(), last),
              result.image.channels.end())
        << last;
    const auto objects = decode(result.image, result.cryptomatte_metadata, "CryptoObject", levels);
    using Coverage = std::map<std::string, float>;
    for (const uint32_t y : {3u, 21u, 38u}) {
      EXPECT_EQ(objects[y * kCryptoImagePx + 5], (Coverage{{"Left", 1.f}})) << levels;
      EXPECT_EQ(objects[y * kCryptoImagePx + 25], (Coverage{{"Right", 1.f}})) << levels;
      EXPECT_EQ(objects[y * kCryptoImagePx + 35], Coverage{}) << levels;
      // The seam halves column 20: two ids, which even 2 levels keep.
      const Coverage seam = objects[y * kCryptoImagePx + 20];
      ASSERT_EQ(seam.size(), 2u) << levels;
      EXPECT_NEAR(seam.at("Left"), 0.5f, 0.13f) << levels;
      EXPECT_NEAR(seam.at("Left") + seam.at("Right"), 1.f, 1e-5f) << levels;
    }
  }
}

TEST(CryptomatteRender, ChannelsAndKeysNameTheViewLayer) {
  RenderOptions options = crypto_options({"Depth", "CryptoObject"});
  options.view_layer = "Shot Layer";
  const Scene scene = crypto_scene();
  const RenderResult result = RenderJob(scene, options, test::loader()).run();
  for (const char* channel :
       {"Shot Layer.Combined.R", "Shot Layer.Combined.A", "Shot Layer.Depth.Z",
        "Shot Layer.CryptoObject00.r", "Shot Layer.CryptoObject02.a"})
    EXPECT_NE(std::find(result.image.channels.begin(), result.image.channels.end(), channel),
              result.image.channels.end())
        << channel;
  for (const std::string& channel : result.image.channels)
    EXPECT_TRUE(channel.starts_with("Shot Layer.")) << channel;
  const std::string key =
      "cryptomatte/" + cryptomatte_hex(cryptomatte_hash("Shot Layer.CryptoObject")).substr(0, 7);
  const std::map<std::string, std::string> metadata(result.cryptomatte_metadata.begin(),
                                                    result.cryptomatte_metadata.end());
  EXPECT_EQ(metadata.at(key + "/name"), "Shot Layer.CryptoObject");
}

}  // namespace
}  // namespace fb
