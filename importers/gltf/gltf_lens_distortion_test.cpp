// A tracked clip's lens distortion as the add-on writes it (docs/blender.md, "What is carried":
// FILMBACK_blender.lens_distortion): read into the camera plugins' parameter names with their JSON
// paths, hostile values refused naming the member, and a camera plugin without the parameters an
// error (the plan marks them required), never a silently undistorted render.
#include "importers/gltf/gltf_lens_distortion.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "core/render/plugin_choice_loader.h"
#include "core/render/shot_plan.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"
#include "support/plugins.h"

namespace fb {
namespace {

constexpr const char* kAt =
    "distortion.gltf: cameras[0].extensions.FILMBACK_blender.lens_distortion";

// One camera of `type` ("perspective" or "orthographic") whose FILMBACK_blender extension holds
// `lens_distortion` (a JSON object's text).
std::filesystem::path write_distortion_gltf(const std::string& lens_distortion,
                                            const std::string& type = "perspective") {
  const std::filesystem::path file = test::scratch_dir() / "distortion.gltf";
  const std::string projection =
      type == "perspective"
          ? R"("perspective": {"yfov": 0.7, "aspectRatio": 1.6, "znear": 0.1})"
          : R"("orthographic": {"xmag": 4, "ymag": 2.5, "znear": 0.1, "zfar": 100})";
  std::ofstream(file) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["FILMBACK_blender"],
  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"name": "Cam", "camera": 0}],
  "cameras": [{"type": ")"
                      << type << R"(", )" << projection
                      << R"(, "extensions": {"FILMBACK_blender": {"focal_length_mm": 28,
      "lens_distortion": )"
                      << lens_distortion << "}}}]}";
  return file;
}

const char* const kPolynomial = R"({"model": "polynomial", "k1": -0.12, "k2": 0.03, "k3": 0,
    "clip_size_px": [256, 160], "focal_length_px": 199.1, "principal_px": [131, 77.5],
    "pixel_aspect": 1})";

std::map<std::string, NamedNumber> numbers_of(const SceneCamera& camera) {
  std::map<std::string, NamedNumber> out;
  for (const NamedNumber& n : camera.lens_distortion)
    out[n.key] = n;
  return out;
}

TEST(GltfLensDistortion, TheModelsCoefficientsAndTheClipBecomeRequiredPluginNumbers) {
  Diagnostics diagnostics;
  const Scene scene = import_gltf(write_distortion_gltf(kPolynomial), diagnostics);
  const auto numbers = numbers_of(scene.cameras.at(0));
  ASSERT_EQ(numbers.size(), 9u);  // k1-k3, the clip's size, focal length, centre, pixel aspect
  EXPECT_EQ(numbers.at("polynomial_k1").value, -0.12);
  EXPECT_EQ(numbers.at("polynomial_k3").value, 0);
  EXPECT_EQ(numbers.at("clip_width_px").value, 256);
  EXPECT_EQ(numbers.at("clip_height_px").value, 160);
  EXPECT_EQ(numbers.at("clip_focal_length_px").value, 199.1);
  EXPECT_EQ(numbers.at("clip_principal_y_px").value, 77.5);
  EXPECT_EQ(numbers.at("clip_pixel_aspect").value, 1);
  EXPECT_TRUE(numbers.at("polynomial_k2").origin.text().ends_with(std::string(kAt) + ".k2"));
  EXPECT_TRUE(
      numbers.at("clip_height_px").origin.text().ends_with(std::string(kAt) + ".clip_size_px[1]"));
  for (const auto& [key, n] : numbers)
    EXPECT_TRUE(n.required) << key;
}

// Blender's panel in millimetres: f_px = f_mm * clip width / sensor width.
TEST(GltfLensDistortion, AFocalLengthInMillimetresIsTheClipsPixelsThroughTheSensor) {
  Diagnostics diagnostics;
  const Scene scene =
      import_gltf(write_distortion_gltf(
                      R"({"model": "brown", "k1": 0.1, "p2": 0.002, "clip_size_px": [1920, 1080],
          "focal_length_mm": 35, "sensor_width_mm": 36, "principal_px": [960, 540]})"),
                  diagnostics);
  const auto numbers = numbers_of(scene.cameras.at(0));
  EXPECT_DOUBLE_EQ(numbers.at("clip_focal_length_px").value, 35.0 * 1920 / 36);
  EXPECT_EQ(numbers.at("brown_p2").value, 0.002);
  EXPECT_EQ(numbers.count("brown_k4"), 0u);  // absent coefficients keep the plugin's 0
  EXPECT_EQ(numbers.at("clip_pixel_aspect").value, 1);
}

TEST(GltfLensDistortion, HostileValuesAreRefusedNamingTheMember) {
  const std::string clip = R"("clip_size_px": [256, 160], "focal_length_px": 200,
      "principal_px": [128, 80])";
  const struct {
    std::string members, at;
  } cases[] = {
      {R"("model": "fisheye", )" + clip, ".model"},
      {R"("k1": 0.1, )" + clip, ".model"},
      {R"("model": "polynomial", "k4": 0.1, )" + clip, ".k4"},
      {R"("model": "nuke", "p1": 0.1, )" + clip, ".p1"},
      {R"("model": "division", "k1": 1e300, )" + clip, ".k1"},
      {R"("model": "division", "k1": "big", )" + clip, ".k1"},
      {R"("model": "polynomial", "k1": 0.1, "focal_length_px": 200, "principal_px": [1, 2])",
       ".clip_size_px"},
      {R"("model": "polynomial", "k1": 0.1, "clip_size_px": [0, 160], "focal_length_px": 200,
          "principal_px": [1, 2])",
       ".clip_size_px[0]"},
      {R"("model": "polynomial", "k1": 0.1, "clip_size_px": [256], "focal_length_px": 200,
          "principal_px": [1, 2])",
       ".clip_size_px"},
      {R"("model": "polynomial", "k1": 0.1, "clip_size_px": [256, 160], "principal_px": [1, 2])",
       ".focal_length_px"},
      {R"("model": "polynomial", "k1": 0.1, "clip_size_px": [256, 160], "focal_length_px": -5,
          "principal_px": [1, 2])",
       ".focal_length_px"},
      {R"("model": "polynomial", "k1": 0.1, "clip_size_px": [256, 160], "focal_length_px": 200)",
       ".principal_px"},
      {R"("model": "polynomial", "k1": 0.1, "pixel_aspect": 0, )" + clip, ".pixel_aspect"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.members);
    const std::string error = test::import_error(write_distortion_gltf("{" + c.members + "}"));
    EXPECT_NE(error.find(std::string(kAt) + c.at + ":"), std::string::npos) << error;
  }
  EXPECT_NE(test::import_error(write_distortion_gltf("[1, 2]")).find(std::string(kAt) + ":"),
            std::string::npos);
}

ShotPlan plan_of(const std::filesystem::path& file, const RenderOptions& options = {}) {
  Diagnostics diagnostics;
  return plan_shot(import_gltf(file, diagnostics), options);
}

// The numbers reach perspective and thinlens; a plugin without them (orthographic, or one typed
// with --camera-model) is an error naming the value's JSON path, not an undistorted render.
TEST(GltfLensDistortion, ACameraPluginWithoutTheParametersIsAnError) {
  const ShotPlan perspective = plan_of(write_distortion_gltf(kPolynomial));
  EXPECT_EQ(perspective.camera_model.name, "perspective");
  EXPECT_NO_THROW(load_camera(test::loader(), perspective));

  RenderOptions thinlens;
  thinlens.camera_model = "thinlens:fstop=4";
  EXPECT_NO_THROW(
      load_camera(test::loader(), plan_of(write_distortion_gltf(kPolynomial), thinlens)));

  try {
    load_camera(test::loader(), plan_of(write_distortion_gltf(kPolynomial, "orthographic")));
    ADD_FAILURE() << "an orthographic camera took a lens distortion";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has no parameter 'polynomial_k1'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(std::string(kAt) + ".k1"), std::string::npos) << e.what();
  }
  RenderOptions typed;
  typed.camera_model = "orthographic";
  EXPECT_THROW(load_camera(test::loader(), plan_of(write_distortion_gltf(kPolynomial), typed)),
               UsageError);
}

}  // namespace
}  // namespace fb
