// The plugin ABI grows without refusing older plugins (plugin_abi.h, "Growth"): plugins built
// against a frozen copy of the previous published header (abi_frozen/) load with the sizes they
// declare and render through the real CLI, and a plugin claiming a newer layout than this host's
// is refused, naming its file and both sizes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "core/image/image_io.h"
#include "core/plugin/abi_layout.h"
#include "core/plugin/loader.h"
#include "core/util/error.h"
#include "sdk/frozen_sizes.h"
#include "support/gltf_builder.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

const fs::path kFrozenPlugins = FB_ABI_FROZEN_PLUGIN_DIR;
const fs::path kFuturePlugins = FB_ABI_FUTURE_PLUGIN_DIR;

struct Outcome {
  int status;
  std::string err;
};

// `filmback <args>` with FILMBACK_PLUGIN_PATH=plugin_dir; the arguments hold no quote.
Outcome run_filmback(const std::string& args, const fs::path& plugin_dir, const fs::path& scratch) {
  const fs::path err = scratch / "stderr.txt";
  const std::string command = "FILMBACK_PLUGIN_PATH='" + plugin_dir.string() +
                              "' '" FB_FILMBACK_EXE "' " + args + " >/dev/null 2>'" + err.string() +
                              "'";
  const int raw = std::system(command.c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, text.str()};
}

// The host's first published layout is the frozen header's, struct by struct, and this host's
// layout is newer where issues 14 and 19 grew it: the frozen plugins below are really older ones.
TEST(AbiGrowth, FirstLayoutIsTheFrozenHeader) {
  const frozen_sizes frozen = frozen_layout_sizes();
  EXPECT_EQ(FirstLayout::plugin, frozen.plugin);
  EXPECT_EQ(FirstLayout::camera_api, frozen.camera_api);
  EXPECT_EQ(FirstLayout::filter_api, frozen.filter_api);
  EXPECT_EQ(FirstLayout::integrator_api, frozen.integrator_api);
  EXPECT_EQ(FirstLayout::hit, frozen.hit);
  EXPECT_EQ(FirstLayout::scene, frozen.scene);
  EXPECT_EQ(FirstLayout::scene_api, frozen.scene_api);
  EXPECT_GT(sizeof(fb_hit), frozen.hit);
  EXPECT_GT(sizeof(fb_scene_api), frozen.scene_api);
  EXPECT_GT(sizeof(fb_scene), frozen.scene);  // issue 19: povray, lamp_count
  EXPECT_GT(sizeof(fb_integrator_api), frozen.integrator_api);
  EXPECT_GT(sizeof(fb_camera_api), frozen.camera_api);
  // Data the plugin only reads grows too; a camera reads the prefix it knows.
  EXPECT_GE(sizeof(fb_camera_setup), frozen.camera_setup);
}

// The loader keeps what the frozen integrator declared, and the fields its table lacks
// (scene_size, scene_api_size; a camera's describe) take the first layout's values.
TEST(AbiGrowth, FrozenIntegratorLoadsWithTheSizesItKnows) {
  const frozen_sizes frozen = frozen_layout_sizes();
  const auto library = PluginLoader({kFrozenPlugins}).load(FB_KIND_INTEGRATOR, "frozendepth");
  const auto& api = library->api<fb_integrator_api>();
  EXPECT_EQ(api.struct_size, frozen.integrator_api);
  EXPECT_EQ(api.hit_size, frozen.hit);
  EXPECT_EQ(api.scene_size, frozen.scene);
  EXPECT_EQ(api.scene_api_size, frozen.scene_api);
  EXPECT_NE(api.radiance, nullptr);
  // The frozen camera's table ends before `describe`, which reads as absent.
  const auto camera = PluginLoader({kFrozenPlugins}).load(FB_KIND_CAMERA, "frozenpinhole");
  EXPECT_EQ(camera->api<fb_camera_api>().struct_size, frozen.camera_api);
  EXPECT_EQ(camera->api<fb_camera_api>().describe, nullptr);
  for (const auto& [kind, name] :
       {std::pair{FB_KIND_CAMERA, "frozenpinhole"}, std::pair{FB_KIND_FILTER, "frozenbox"}})
    EXPECT_NO_THROW(PluginLoader({kFrozenPlugins}).load(kind, name)) << name;
}

// A square 8x8 shot with a 90-degree field of view of a plane 2 m in front of the camera, base
// colour 0.25, rendered by the three frozen plugins. Each pixel's ray goes through its centre
// (frozenpinhole), so with d = (x, y, -1), x and y the centre's place in [-1, 1] (tan 45 deg = 1),
// the integrator's channels are exactly: R = depth = 2 m (its hits written with its own stride by
// intersect_batch), G = t = 2 |d| (intersect), B = 0.25 (a field past both normals). A host that
// wrote this host's longer records, or handed it a longer scene table, fails every pixel but the
// first of a batch, or every pixel (-1).
TEST(AbiGrowth, FrozenPluginsRenderThroughTheCli) {
  constexpr double kDistance = 2.0, kBase = 0.25;
  constexpr int kSize = 8;
  const fs::path scratch = test::scratch_dir();
  test::GltfBuilder gltf;
  const int material = gltf.material({float(kBase), float(kBase), float(kBase)});
  const float e = float(3 * kDistance), z = float(-kDistance);
  const int quad =
      gltf.mesh({{-e, -e, z}, {e, -e, z}, {e, e, z}, {-e, e, z}}, {0, 1, 2, 0, 2, 3}, material);
  const int camera = gltf.perspective_camera(M_PI / 2, 1.0, 0.01, 100);
  test::GltfBuilder::Node plane_node, camera_node;
  plane_node.mesh = quad;
  camera_node.camera = camera;
  gltf.node(plane_node);
  gltf.node(camera_node);
  const fs::path scene = gltf.write(scratch / "plane.gltf");
  const fs::path image = scratch / "frozen.exr";
  const Outcome run = run_filmback("render '" + scene.string() + "' --res " +
                                       std::to_string(kSize) + "x" + std::to_string(kSize) +
                                       " --spp 4 -q --camera-model frozenpinhole --filter "
                                       "frozenbox --integrator frozendepth -o '" +
                                       image.string() + "'",
                                   kFrozenPlugins, scratch);
  ASSERT_EQ(run.status, 0) << run.err;
  const Image out = read_image(image);
  ASSERT_EQ(out.width, uint32_t(kSize));
  ASSERT_EQ(out.height, uint32_t(kSize));
  ASSERT_GE(out.channels.size(), 3u);
  for (uint32_t py = 0; py < out.height; ++py)
    for (uint32_t px = 0; px < out.width; ++px) {
      const double x = 2 * (px + 0.5) / kSize - 1, y = 1 - 2 * (py + 0.5) / kSize;
      const double t = kDistance * std::sqrt(1 + x * x + y * y);
      // float rays and hits: a few ulp of the 2..3.5 m distances
      EXPECT_NEAR(out.at(px, py, 0), kDistance, 1e-5) << px << "," << py;
      EXPECT_NEAR(out.at(px, py, 1), t, 1e-5 * t) << px << "," << py;
      EXPECT_NEAR(out.at(px, py, 2), kBase, 1e-6) << px << "," << py;
    }
}

// A plugin from a newer SDK, whose hit records are longer than this host's, is refused: loading
// it in process, and rendering with it (exit 1, nothing written), naming the file and both sizes.
TEST(AbiGrowth, NewerPluginIsRefusedNamingFileAndSizes) {
  const fs::path file = kFuturePlugins / plugin_file_name(FB_KIND_INTEGRATOR, "future");
  const std::string reason = "plugin newer than this filmback: its fb_hit (hit_size) is " +
                             std::to_string(sizeof(fb_hit) + 4 * sizeof(float)) +
                             " bytes, this filmback's is " + std::to_string(sizeof(fb_hit)) +
                             " (update filmback, or rebuild the plugin against this SDK)";
  try {
    PluginLoader({kFuturePlugins}).load(FB_KIND_INTEGRATOR, "future");
    ADD_FAILURE() << "the future integrator loaded";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), file.string() + ": " + reason);
  }
  const fs::path scratch = test::scratch_dir();
  const fs::path image = scratch / "future.exr";
  const Outcome run =
      run_filmback("render '" FB_DEFAULT_SCENE "' --res 4x4 --spp 1 -q --integrator future -o '" +
                       image.string() + "'",
                   kFuturePlugins, scratch);
  EXPECT_EQ(run.status, 1) << run.err;
  EXPECT_NE(run.err.find(file.string() + ": " + reason), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(image));
}

}  // namespace
}  // namespace fb
