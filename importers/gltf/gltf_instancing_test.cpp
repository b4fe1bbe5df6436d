// EXT_mesh_gpu_instancing and the bound on instances a file may make (importers/gltf/
// gltf_instancing.h).
#include "importers/gltf/gltf_instancing.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"

namespace fb {
namespace {

// A file whose one triangle (accessor 0) is drawn by `nodes` nodes, each through
// EXT_mesh_gpu_instancing with `translations` (accessor 1; its declared count `declared_count`)
// and, when `primitives` > 1, by that many primitives of its one mesh.
std::filesystem::path instanced_file(const std::vector<Vec3f>& translations, size_t declared_count,
                                     size_t primitives = 1, size_t nodes = 1) {
  std::vector<unsigned char> bytes(36 + 12 * translations.size());
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::memcpy(bytes.data(), triangle, 36);
  std::memcpy(bytes.data() + 36, translations.data(), 12 * translations.size());
  std::string prims;
  for (size_t p = 0; p < primitives; ++p)
    prims += std::string(p ? "," : "") + R"({"attributes":{"POSITION":0}})";
  std::string node_list, roots;
  for (size_t n = 0; n < nodes; ++n) {
    node_list +=
        std::string(n ? "," : "") +
        R"({"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":1}}}})";
    roots += std::string(n ? "," : "") + std::to_string(n);
  }
  const std::string json =
      R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_mesh_gpu_instancing"],)"
      R"("buffers":[{"byteLength":)" +
      std::to_string(bytes.size()) + R"(,"uri":"data:application/octet-stream;base64,)" +
      test::base64(bytes) +
      R"("}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},)"
      R"({"buffer":0,"byteOffset":36,"byteLength":)" +
      std::to_string(12 * translations.size()) +
      R"(}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
      R"("min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5126,"count":)" +
      std::to_string(declared_count) +
      R"(,"type":"VEC3"}],)"
      R"("meshes":[{"primitives":[)" +
      prims + R"(]}],"nodes":[)" + node_list + R"(],"scenes":[{"nodes":[)" + roots +
      R"(]}],"scene":0})";
  const auto file = test::scratch_dir() / "instanced.gltf";
  std::ofstream(file) << json;
  return file;
}

TEST(GltfInstancing, EachTranslationPlacesTheNodesMeshOnce) {
  const std::vector<Vec3f> translations = {{0, 0, 0}, {2, 0, 0}, {0, 0, -3}};
  Diagnostics diagnostics;
  const Scene scene = import_gltf(instanced_file(translations, 3), diagnostics);
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(scene.instances[i].mesh, 0u);
    const Vec3d moved = scene.instances[i].world_from_object.point({1, 0, 0});
    const Vec3d expected = Vec3d(1, 0, 0) + Vec3d(translations[i]);
    EXPECT_EQ(moved.x, expected.x) << i;
    EXPECT_EQ(moved.y, expected.y) << i;
    EXPECT_EQ(moved.z, expected.z) << i;
  }
}

// 10^9 instances declared by a file of a few hundred bytes: refused before anything is read or
// allocated, naming the attribute.
TEST(GltfInstancing, ABillionInstancesAreRefusedNamingTheAttribute) {
  const std::string error = test::import_error(instanced_file({{0, 0, 0}}, 1000000000));
  EXPECT_NE(error.find("nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.TRANSLATION"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("1000000000 more"), std::string::npos) << error;
  EXPECT_NE(error.find("at most 4194304"), std::string::npos) << error;
}

// 3000 primitives drawn 1500 times (4.5 million instances, past 2^22) by a file of 100 KB: refused
// at the node's mesh before a single instance is made.
TEST(GltfInstancing, PrimitivesTimesInstancesAreBoundedToo) {
  const std::string error =
      test::import_error(instanced_file(std::vector<Vec3f>(1500), 1500, 3000));
  EXPECT_NE(error.find("nodes[0].mesh"), std::string::npos) << error;
  EXPECT_NE(error.find("4500000 more"), std::string::npos) << error;
}

TEST(GltfInstancing, AttributesOfDifferentCountsAreRefused) {
  const auto file = instanced_file({{0, 0, 0}, {1, 0, 0}}, 2);
  std::string json;
  {
    std::ifstream in(file);
    json.assign(std::istreambuf_iterator<char>(in), {});
  }
  // SCALE from the triangle's accessor: 3 values against TRANSLATION's 2.
  const std::string from = R"("TRANSLATION":1)";
  json.replace(json.find(from), from.size(), R"("TRANSLATION":1,"SCALE":0)");
  std::ofstream(file) << json;
  const std::string error = test::import_error(file);
  EXPECT_NE(error.find("EXT_mesh_gpu_instancing.attributes.SCALE"), std::string::npos) << error;
  EXPECT_NE(error.find("3 instances, expected 2"), std::string::npos) << error;
}

}  // namespace
}  // namespace fb
