// A panoramic camera as the add-on writes it (FILMBACK_blender.panorama): read into the panoramic
// projection and SceneCamera::model with each value's JSON path, planned to its camera plugin, and
// hostile panoramas (an unknown type, a key the type does not take, a value that is no finite
// number, one beyond the plugin's range) refused naming the file and the JSON path.
#include <gtest/gtest.h>

#include <fstream>

#include "core/render/plugin_choice_loader.h"
#include "core/render/shot_plan.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

constexpr const char* kPath = "cameras[0].extensions.FILMBACK_blender.panorama";

// One camera whose FILMBACK_blender extension has `panorama` (a JSON value) beside Blender's lens.
std::filesystem::path write_panorama_gltf(const std::string& panorama) {
  const std::filesystem::path file = test::scratch_dir() / "panorama.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["FILMBACK_blender"],
  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"name": "Cam", "camera": 0}],
  "cameras": [{"type": "perspective",
    "perspective": {"yfov": 0.4, "aspectRatio": 2.0, "znear": 0.1, "zfar": 100},
    "extensions": {"FILMBACK_blender": {"focal_length_mm": 50, "sensor_width_mm": 36,
      "sensor_fit": "auto", "clip_near_m": 0.1, "clip_far_m": 100, "panorama": )"
                      << panorama << "}}}]}";
  return file;
}

std::string panorama_error(const std::string& panorama) {
  Diagnostics diagnostics;
  try {
    const Scene scene = import_gltf(write_panorama_gltf(panorama), diagnostics);
    const ShotPlan plan = plan_shot(scene, {});
    load_camera(test::loader(), plan);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GltfPanorama, IsReadIntoThePanoramicProjectionWithEachValuesOrigin) {
  Diagnostics diagnostics;
  const Scene scene = import_gltf(
      write_panorama_gltf(
          R"({"type": "fisheye_equisolid", "fisheye_lens_mm": 8, "fisheye_fov_rad": 3})"),
      diagnostics);
  ASSERT_EQ(scene.cameras.size(), 1u);
  const SceneCamera& camera = scene.cameras[0];
  EXPECT_EQ(camera.physical.projection, uint32_t(FB_PROJECTION_PANORAMIC));
  ASSERT_TRUE(camera.model);
  EXPECT_EQ(camera.model->kind, "fisheye_equisolid");
  EXPECT_EQ(camera.model->origin.path, std::string(kPath) + ".type");
  ASSERT_EQ(camera.model->numbers.size(), 2u);
  for (const NamedNumber& n : camera.model->numbers) {  // in the file's key order
    EXPECT_EQ(n.value, n.key == "fisheye_lens_mm" ? 8 : 3) << n.key;
    EXPECT_EQ(n.origin.path, std::string(kPath) + "." + n.key);
  }
  EXPECT_EQ(diagnostics.count(), 0u) << "no yfov agreement for a panorama's stand-in";
  // The plan renders it with the kind's plugin, which takes the values.
  const ShotPlan plan = plan_shot(scene, {});
  EXPECT_EQ(plan.camera_model.name, "fisheye_equisolid");
  EXPECT_NO_THROW(load_camera(test::loader(), plan));
  // A type without values.
  EXPECT_EQ(panorama_error(R"({"type": "mirrorball"})"), "(no error)");
}

TEST(GltfPanorama, HostilePanoramasAreRefusedNamingTheJsonPath) {
  const struct {
    const char* panorama;
    std::string path, expected;
  } rows[] = {
      {R"({"type": "stereographic"})", ".type", "expected one of equirectangular"},
      {R"({"fisheye_fov_rad": 3})", ".type", "absent"},
      {R"({"type": "fisheye_equidistant", "fov": 3})", ".fov", "takes fisheye_fov_rad"},
      {R"({"type": "mirrorball", "k0": 0})", ".k0", "takes no values"},
      {R"({"type": "fisheye_equidistant", "fisheye_fov_rad": "wide"})", ".fisheye_fov_rad",
       "expected a number"},
      {R"({"type": "fisheye_polynomial", "k1": 1e300})", ".k1", "expected a number"},
      // Beyond the plugin's range: refused when the plugin is made, still naming the value.
      {R"({"type": "fisheye_equidistant", "fisheye_fov_rad": 7})", ".fisheye_fov_rad",
       "fisheye_fov_rad"},
      {R"({"type": "equirectangular", "latitude_max_rad": 2})", ".latitude_max_rad",
       "latitude_max_rad"},
  };
  for (const auto& row : rows) {
    const std::string error = panorama_error(row.panorama);
    EXPECT_NE(error.find("panorama.gltf: " + std::string(kPath) + row.path), std::string::npos)
        << row.panorama << " -> " << error;
    EXPECT_NE(error.find(row.expected), std::string::npos) << row.panorama << " -> " << error;
  }
  EXPECT_NE(panorama_error("3").find("FILMBACK_blender.panorama"), std::string::npos);
}

}  // namespace
}  // namespace fb
