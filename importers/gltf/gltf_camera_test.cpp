// Cameras and shot settings as Blender's add-on writes them (docs/blender.md, "Cameras"): the
// precedence FILMBACK_blender > EXT_camera_physical > extras > yfov taking a source whole (a table
// of source combinations and options, with each value's origin), the 0.01 degree agreement check,
// focus tracks, the scene's settings, and errors naming the file and JSON path.
#include "importers/gltf/gltf_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "core/render/render_job.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"

namespace fb {
namespace {

// yfov of Blender's default camera (50 mm on a 36 mm sensor, AUTO fit) at 16:9.
const double kDefaultYfov = 2 * std::atan(36.0 / 100 / (16.0 / 9));

// One camera node; `camera_members` and `scene_members` are spliced into the camera and scene
// objects ("" for none).
std::filesystem::path write_camera_gltf(const std::string& camera_members,
                                        const std::string& scene_members = "",
                                        double yfov = kDefaultYfov) {
  const std::filesystem::path file = test::scratch_dir() / "camera.gltf";
  char perspective[160];
  std::snprintf(
      perspective, sizeof perspective,
      R"("perspective": {"yfov": %.17g, "aspectRatio": 1.7777777777777777, "znear": 0.1})", yfov);
  std::ofstream(file) << R"({"asset": {"version": "2.0"},
  "extensionsUsed": ["FILMBACK_blender", "EXT_camera_physical"],
  "scene": 0, "scenes": [{"nodes": [0])"
                      << (scene_members.empty() ? "" : ", " + scene_members) << R"(}],
  "nodes": [{"name": "Cam", "camera": 0}],
  "cameras": [{"name": "Lens", "type": "perspective", )"
                      << perspective << (camera_members.empty() ? "" : ", " + camera_members)
                      << "}]}";
  return file;
}

// One row of the precedence table: the camera's sources as JSON members, options typed on the
// command line, and what the camera must hold: each listed value and a fragment of its origin.
struct Expected {
  CameraValue value;
  double number;
  const char* origin;
};
struct PrecedenceCase {
  const char* name;
  const char* camera_members;
  CameraOverrides typed;
  std::vector<Expected> expected;
  const char* warning;  // a fragment of the one warning expected, or nullptr for none
  double yfov = kDefaultYfov;
};

constexpr const char* kOurs = "cameras[0].extensions.FILMBACK_blender.";
constexpr const char* kExt = "cameras[0].extensions.EXT_camera_physical.";
constexpr const char* kExtras = "cameras[0].extras.";
using V = CameraValue;

std::vector<PrecedenceCase> precedence_cases() {
  // 35 mm on 36 x 24 mm, vertical fit, at 16:9: yfov = 2 atan(12 / 35).
  const double vertical_35_focal = 35;
  CameraOverrides typed_pinhole;
  typed_pinhole.fstop = fstop_from(0);
  typed_pinhole.focal_length_mm = 85;
  return {
      {"core yfov alone: Blender's 36 mm AUTO, a pinhole",
       "",
       {},
       {{V::kFocalLength, 50, "cameras[0].perspective.yfov"},
        {V::kSensorWidth, 36, "default"},
        {V::kFstop, HUGE_VAL, "no source names it: a pinhole"},
        {V::kClipNear, 0.1, "cameras[0].perspective.znear"}},
       nullptr},
      {"bug 1: extras named like ours give no depth of field when FILMBACK_blender describes",
       R"("extras": {"fstop": 2.8, "shift_x": 0.1, "focal_length_mm": 20},
          "extensions": {"FILMBACK_blender": {"focal_length_mm": 50, "sensor_width_mm": 36,
                         "sensor_height_mm": 24, "sensor_fit": "auto"}})",
       {},
       {{V::kFocalLength, 50, "FILMBACK_blender.focal_length_mm"},
        {V::kFstop, HUGE_VAL, "FILMBACK_blender names none: depth of field off"},
        {V::kShiftX, 0, "FILMBACK_blender names none"}},
       "cameras[0].extras: focal_length_mm, shift_x, fstop ignored: FILMBACK_blender describes"},
      {"bug 2: extras' sensor and fit without a focal length: the focal length from yfov under "
       "them",
       R"("extras": {"sensor_width_mm": 24, "sensor_height_mm": 36, "sensor_fit": "vertical"})",
       {},
       // yfov = 2 atan(18 / 50 / (16/9)), vertical fit on 36 mm: f = 18 / tan(yfov / 2)
       {{V::kFocalLength, 50 * 16.0 / 9, "cameras[0].perspective.yfov (under the sensor"},
        {V::kSensorHeight, 36, "extras.sensor_height_mm"},
        {V::kSensorFit, FB_SENSOR_FIT_VERTICAL, "extras.sensor_fit"}},
       nullptr},
      {"EXT_camera_physical: lens and sensor; extras fill the aperture and fit it cannot express",
       R"("extras": {"fstop": 4, "sensor_fit": "vertical", "focal_length_mm": 20},
          "extensions": {"EXT_camera_physical": {"focalLength": 0.035,
                                                 "sensorSize": [0.036, 0.024]}})",
       {},
       {{V::kFocalLength, vertical_35_focal, "EXT_camera_physical.focalLength"},
        {V::kSensorWidth, 36, "EXT_camera_physical.sensorSize[0]"},
        {V::kSensorFit, FB_SENSOR_FIT_VERTICAL, "extras.sensor_fit"},
        {V::kFstop, 4, "extras.fstop"}},
       "cameras[0].extras: focal_length_mm ignored: EXT_camera_physical describes",
       2 * std::atan(12.0 / 35)},
      {"FILMBACK_blender over EXT_camera_physical: EXT's sensor never fills ours",
       R"("extensions": {"EXT_camera_physical": {"focalLength": 0.035, "sensorSize": [0.024, 0.016]},
                         "FILMBACK_blender": {"focal_length_mm": 35, "sensor_fit": "vertical"}})",
       {},
       {{V::kFocalLength, 35, "FILMBACK_blender.focal_length_mm"},
        {V::kSensorWidth, 36, "default"},
        {V::kSensorHeight, 24, "default"}},
       "EXT_camera_physical: sensor_width_mm, sensor_height_mm ignored",
       2 * std::atan(12.0 / 35)},
      {"options replace the highest source, and say so",
       R"("extensions": {"FILMBACK_blender": {"focal_length_mm": 50, "sensor_fit": "auto",
                         "fstop": 2, "focus_distance_m": 3}})",
       typed_pinhole,
       {{V::kFocalLength, 85, "--focal-length"},
        {V::kFstop, HUGE_VAL, "--fstop"},
        {V::kFocusDistance, 3, "FILMBACK_blender.focus_distance_m"}},
       nullptr},
      {"fstop 0 in FILMBACK_blender is depth of field off",
       R"("extensions": {"FILMBACK_blender": {"fstop": 0}}, "extras": {"fstop": 0})",
       {},
       {{V::kFstop, HUGE_VAL, "FILMBACK_blender.fstop"}},
       nullptr},
  };
}

TEST(GltfCamera, PrecedenceTakesTheHighestSourceWholeAndKeepsEachValuesOrigin) {
  for (const PrecedenceCase& c : precedence_cases()) {
    SCOPED_TRACE(c.name);
    Diagnostics d;
    const Scene scene = import_gltf(write_camera_gltf(c.camera_members, "", c.yfov), d);
    SceneCamera camera = scene.cameras.at(0);
    c.typed.apply(camera);
    for (const Expected& e : c.expected) {
      SCOPED_TRACE(camera_value_name(e.value));
      if (std::isinf(e.number)) {
        EXPECT_EQ(camera_value(camera.physical, e.value), e.number);
      } else {
        EXPECT_NEAR(camera_value(camera.physical, e.value), e.number, 1e-9 * std::abs(e.number));
      }
      EXPECT_NE(camera.origin(e.value).text().find(e.origin), std::string::npos)
          << camera.origin(e.value).text();
    }
    if (c.warning) {
      ASSERT_EQ(d.count(), 1u);
      EXPECT_NE(d.messages().at(0).find(c.warning), std::string::npos) << d.messages().at(0);
    } else {
      EXPECT_EQ(d.count(), 0u) << (d.count() ? d.messages().at(0) : "");
    }
  }
}

// Bug 2 as a render would see it: the frame is yfov's, within 1e-9 degrees (it was 13.7 px off).
TEST(GltfCamera, ExtrasWithoutAFocalLengthKeepYfovsFrame) {
  Diagnostics d;
  const Scene scene = import_gltf(
      write_camera_gltf(
          R"("extras": {"sensor_width_mm": 24, "sensor_height_mm": 36, "sensor_fit": "vertical"})"),
      d);
  const CameraQuantities q = describe_camera(scene.cameras.at(0).physical, 1920, 1080);
  EXPECT_NEAR(q.vertical_fov_deg, kDefaultYfov * 180 / std::numbers::pi, 1e-9);
}

TEST(GltfCamera, ExtCameraPhysicalAloneTakesTheFitThatGivesYfov) {
  // 35 mm on 36 x 24 mm, vertical fit: yfov = 2 atan(12 / 35).
  Diagnostics d;
  const Scene scene = import_gltf(
      write_camera_gltf(
          R"("extensions": {"EXT_camera_physical": {"focalLength": 0.035, "sensorSize": [0.036, 0.024]}})",
          "", 2 * std::atan(12.0 / 35)),
      d);
  const PhysicalCamera& c = scene.cameras.at(0).physical;
  EXPECT_DOUBLE_EQ(c.focal_length_mm, 35);
  EXPECT_DOUBLE_EQ(c.sensor_height_mm, 24);
  EXPECT_EQ(c.sensor_fit, uint32_t(FB_SENSOR_FIT_VERTICAL));
  EXPECT_EQ(d.count(), 0u);
}

TEST(GltfCamera, ExtCameraPhysicalThatContradictsYfovIsWarnedAndYfovUsed) {
  Diagnostics d;
  const Scene scene = import_gltf(
      write_camera_gltf(
          R"("extensions": {"EXT_camera_physical": {"focalLength": 0.2, "sensorSize": [0.036, 0.024]}})"),
      d);
  ASSERT_EQ(d.count(), 1u);
  EXPECT_NE(d.messages().at(0).find("using yfov"), std::string::npos) << d.messages().at(0);
  EXPECT_NEAR(scene.cameras.at(0).physical.focal_length_mm, 50, 1e-9);  // yfov's 36 mm AUTO
}

TEST(GltfCamera, DisagreementBeyondOneHundredthOfADegreeIsWarnedNamingTheSourceUsed) {
  Diagnostics d;
  const Scene scene = import_gltf(
      write_camera_gltf(R"("extensions": {"FILMBACK_blender": {"focal_length_mm": 50.1}})"), d);
  ASSERT_EQ(d.count(), 1u);
  EXPECT_NE(d.messages().at(0).find("using FILMBACK_blender"), std::string::npos)
      << d.messages().at(0);
  EXPECT_EQ(scene.cameras.at(0).physical.focal_length_mm, 50.1);
  // 50.001 mm changes the field of view by 0.0005 degrees: no warning.
  Diagnostics quiet;
  import_gltf(
      write_camera_gltf(R"("extensions": {"FILMBACK_blender": {"focal_length_mm": 50.001}})"),
      quiet);
  EXPECT_EQ(quiet.count(), 0u);
}

TEST(GltfCamera, LensTrackIsInterpolatedBetweenFramesAndHeldBeyond) {
  Diagnostics d;
  const Scene scene =
      import_gltf(write_camera_gltf(R"("extensions": {"FILMBACK_blender": {"fstop": 2,
      "focus_distance_m": 3, "focal_length_mm": 30, "per_frame": {"first_frame": 10, "focus_distance_m": [2, 4, 8],
      "focal_length_mm": [30, 40], "fstop": [2.8, 1.4, 2], "shift_x": [0, 0.1], "shift_y": [-0.1]}}})"),
                  d);
  const SceneCamera& camera = scene.cameras.at(0);
  const LensTrack& t = camera.lens_track.value();
  using V = CameraValue;
  EXPECT_EQ(t.at(V::kFocusDistance, 5), 2);
  EXPECT_EQ(t.at(V::kFocusDistance, 10), 2);
  EXPECT_EQ(t.at(V::kFocusDistance, 10.5), 3);
  EXPECT_EQ(t.at(V::kFocusDistance, 12), 8);
  EXPECT_EQ(t.at(V::kFocusDistance, 100), 8);
  EXPECT_EQ(t.at(V::kFocalLength, 10.25), 32.5);
  EXPECT_EQ(t.at(V::kFocalLength, 12), 40);  // each list held beyond its own end
  EXPECT_EQ(t.at(V::kFstop, 11.5), 1.7);
  EXPECT_EQ(t.at(V::kShiftX, 10.5), 0.05);
  EXPECT_EQ(t.at(V::kShiftY, 11), -0.1);
  EXPECT_FALSE(t.tracks(V::kSensorWidth));
  PhysicalCamera at_11 = camera.physical;
  t.apply(11, at_11);
  EXPECT_EQ(at_11.focal_length_mm, 40);
  EXPECT_EQ(at_11.focus_distance_m, 4);
  EXPECT_EQ(at_11.fstop, 1.4);
  EXPECT_EQ(at_11.shift_x, 0.1);
  EXPECT_EQ(camera.origin(V::kFocalLength).path,
            "cameras[0].extensions.FILMBACK_blender.per_frame.focal_length_mm");
  EXPECT_EQ(camera.origin(V::kShiftY).path,
            "cameras[0].extensions.FILMBACK_blender.per_frame.shift_y");
}

// Files the add-on wrote before per_frame keep their focus track.
TEST(GltfCamera, TheFocusTrackBeforePerFrameIsStillRead) {
  Diagnostics d;
  const Scene scene =
      import_gltf(write_camera_gltf(R"("extensions": {"FILMBACK_blender": {"fstop": 2,
      "focus_distance_m": 3, "focus_distance_per_frame_m": {"first_frame": 10, "values": [2, 4]}}})"),
                  d);
  const SceneCamera& camera = scene.cameras.at(0);
  const LensTrack& t = camera.lens_track.value();
  EXPECT_EQ(t.at(CameraValue::kFocusDistance, 10.5), 3);
  EXPECT_FALSE(t.tracks(CameraValue::kFocalLength));
  EXPECT_EQ(camera.origin(CameraValue::kFocusDistance).path,
            "cameras[0].extensions.FILMBACK_blender.focus_distance_per_frame_m.values");
  EXPECT_NE(
      test::import_error(
          write_camera_gltf(R"("extensions": {"FILMBACK_blender": {"focus_distance_per_frame_m":
      {"first_frame": 1, "values": [2, "x"]}}})"))
          .find("focus_distance_per_frame_m.values[1]: expected a number"),
      std::string::npos);
}

TEST(GltfCamera, HostileLensTracksAreErrorsNamingTheJsonPath) {
  const auto error = [](const std::string& per_frame) {
    return test::import_error(write_camera_gltf(
        R"("extensions": {"FILMBACK_blender": {"per_frame": )" + per_frame + "}}"));
  };
  const std::string path = "cameras[0].extensions.FILMBACK_blender.per_frame";
  const auto names = [](const std::string& text, const std::string& fragment) {
    return text.find(fragment) != std::string::npos;
  };
  EXPECT_PRED2(names, error(R"({"first_frame": 1, "focus_distance_m": [1, "NaN"]})"),
               path + ".focus_distance_m[1]: expected a number");
  EXPECT_PRED2(names, error(R"({"first_frame": 1, "focal_length_mm": [50, 1e300]})"),
               path + ".focal_length_mm[1]: expected a number in [0.001, 100000]");
  EXPECT_PRED2(names, error(R"({"first_frame": 1, "fstop": [2, 0]})"),
               path + ".fstop[1]: expected a number in [1e-06, 1e+06]");
  EXPECT_PRED2(names, error(R"({"first_frame": 1, "shift_x": [0, -101]})"),
               path + ".shift_x[1]: expected a number in [-100, 100]");
  // tinygltf drops an empty array: the member reads as absent.
  EXPECT_PRED2(names, error(R"({"first_frame": 1, "shift_y": []})"),
               path + ": expected at least one of focal_length_mm");
  EXPECT_PRED2(names, error(R"({"focal_length_mm": [50]})"),
               path + ".first_frame: expected the first frame's number");
  EXPECT_PRED2(names, error(R"({"first_frame": 0.5, "focal_length_mm": [50]})"),
               path + ".first_frame: expected");
  EXPECT_PRED2(names, error(R"({"first_frame": 1})"),
               path + ": expected at least one of focal_length_mm");
  EXPECT_PRED2(names, error("[1, 2]"), path + ": expected an object");
  std::string huge = R"({"first_frame": 0, "focal_length_mm": [50)";
  for (int i = 0; i < 100000; ++i)
    huge += ",50";
  EXPECT_PRED2(names, error(huge + "]}"),
               path + ".focal_length_mm: expected an array of at most 100000 numbers");
}

TEST(GltfCamera, FstopZeroIsBlendersDepthOfFieldOff) {
  Diagnostics d;
  const Scene scene =
      import_gltf(write_camera_gltf(R"("extensions": {"FILMBACK_blender": {"fstop": 0}})"), d);
  EXPECT_FALSE(scene.cameras.at(0).physical.has_aperture());
}

TEST(GltfShot, SceneExtensionCarriesBlendersRenderSettings) {
  Diagnostics d;
  const Scene scene = import_gltf(
      write_camera_gltf("", R"("extensions": {"FILMBACK_blender": {"resolution_x_px": 960,
      "resolution_y_px": 540, "pixel_aspect_x": 2, "pixel_aspect_y": 1, "fps": 30, "fps_base": 1.001,
      "frame": 7, "shutter_open_s": -0.01, "shutter_close_s": 0.01, "shutter_curve": [0, 1, 0],
      "filter_type": "GAUSSIAN", "filter_width_px": 2, "film_exposure": 0.5,
      "view_transform": "Standard", "exposure_stops": 0}})"),
      d);
  const ShotSettings& s = scene.settings;
  EXPECT_EQ(s.width_px, 960u);
  EXPECT_EQ(s.pixel_aspect, 2.0);
  EXPECT_EQ(s.fps, 30.0);  // the timeline of the keys, frame / fps, as Blender exports them
  EXPECT_EQ(s.frame, 7.0);
  EXPECT_EQ(s.shutter_curve, (std::vector<double>{0, 1, 0}));
  ASSERT_TRUE(s.filter);
  EXPECT_EQ(s.filter->type, PixelFilterSetting::Type::kGaussian);
  EXPECT_EQ(s.filter->width_px, 2.0);
  EXPECT_EQ(s.filter->origin.path, "scenes[0].extensions.FILMBACK_blender");
  EXPECT_EQ(s.filter->origin.file, scene.file.string());
  EXPECT_EQ(s.film_exposure, 0.5);
  EXPECT_EQ(d.count(), 0u);
}

// Cycles' Sampling > Adaptive Sampling, as the add-on exports it; a threshold outside Blender's
// [0, 1] is refused naming the key.
TEST(GltfShot, AdaptiveSamplingIsCyclesSettings) {
  Diagnostics d;
  const auto settings = [&](const std::string& members) {
    return import_gltf(
               write_camera_gltf("", R"("extensions": {"FILMBACK_blender": {)" + members + "}}"), d)
        .settings;
  };
  const ShotSettings s = settings(
      R"("use_adaptive_sampling": true, "adaptive_threshold": 0.02, "adaptive_min_samples": 32)");
  ASSERT_TRUE(s.adaptive);
  EXPECT_TRUE(s.adaptive->use);
  EXPECT_EQ(s.adaptive->threshold, 0.02);
  EXPECT_EQ(s.adaptive->min_samples, 32u);
  EXPECT_FALSE(settings(R"("use_adaptive_sampling": false)").adaptive->use);
  EXPECT_FALSE(settings(R"("film_exposure": 1)").adaptive);  // older exports: not said
  try {
    settings(R"("use_adaptive_sampling": true, "adaptive_threshold": 2)");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("adaptive_threshold"), std::string::npos) << e.what();
  }
}

TEST(GltfShot, RollingShutterIsCyclesTopToBottomWithinTheShutter) {
  Diagnostics d;
  const auto settings = [&](const std::string& members) {
    return import_gltf(
               write_camera_gltf("", R"("extensions": {"FILMBACK_blender": {)" + members + "}}"), d)
        .settings;
  };
  const std::string shutter = R"("shutter_open_s": -0.01, "shutter_close_s": 0.01, )";
  EXPECT_EQ(settings(shutter + R"("rolling_shutter_type": "TOP", "rolling_shutter_duration": 0.25)")
                .rolling_shutter_duration,
            0.25);
  EXPECT_EQ(settings(shutter + R"("rolling_shutter_type": "TOP")").rolling_shutter_duration,
            0.1);  // Cycles' default
  EXPECT_FALSE(
      settings(shutter + R"("rolling_shutter_type": "NONE", "rolling_shutter_duration": 0.5)")
          .rolling_shutter_duration);
  EXPECT_FALSE(settings(shutter.substr(0, shutter.size() - 2)).rolling_shutter_duration);
  const std::string path = "scenes[0].extensions.FILMBACK_blender.";
  const auto error = [&](const std::string& members) {
    return test::import_error(
        write_camera_gltf("", R"("extensions": {"FILMBACK_blender": {)" + members + "}}"));
  };
  EXPECT_NE(error(shutter + R"("rolling_shutter_type": "BOTTOM")")
                .find(path + "rolling_shutter_type: 'BOTTOM', expected NONE or TOP"),
            std::string::npos);
  EXPECT_NE(error(shutter + R"("rolling_shutter_type": "TOP", "rolling_shutter_duration": 1.5)")
                .find(path + "rolling_shutter_duration: expected a number in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error(shutter + R"("rolling_shutter_type": "TOP", "rolling_shutter_duration": "NaN")")
                .find(path + "rolling_shutter_duration: expected a number"),
            std::string::npos);
  EXPECT_NE(error(R"("rolling_shutter_type": "TOP")")
                .find(path + "rolling_shutter_type: TOP without shutter_open_s"),
            std::string::npos);
}

TEST(GltfShot, ViewSettingsAreRead) {
  Diagnostics d;
  const ViewSettings v =
      import_gltf(
          write_camera_gltf("", R"("extensions": {"FILMBACK_blender": {"view_transform": "Filmic",
      "look": "Medium High Contrast", "display_device": "sRGB", "exposure_stops": 0.7,
      "gamma": 1.2, "dither_intensity": 0.5}})"),
          d)
          .settings.view;
  EXPECT_EQ(v.view_transform, "Filmic");
  EXPECT_EQ(v.look, "Medium High Contrast");
  EXPECT_EQ(v.display_device, "sRGB");
  EXPECT_EQ(v.exposure_stops, 0.7);
  EXPECT_EQ(v.gamma, 1.2);
  EXPECT_EQ(v.dither_intensity, 0.5);
  EXPECT_EQ(d.count(), 0u);
  // A file from Blender that does not say: Blender's defaults (dither 1); one that names no view:
  // the plain sRGB curve, no dither.
  const ViewSettings blender =
      import_gltf(write_camera_gltf(
                      "", R"("extensions": {"FILMBACK_blender": {"view_transform": "Standard"}})"),
                  d)
          .settings.view;
  EXPECT_EQ(blender.look, "None");
  EXPECT_EQ(blender.gamma, 1.0);
  EXPECT_EQ(blender.dither_intensity, 1.0);
  const ViewSettings other = import_gltf(write_camera_gltf("", ""), d).settings.view;
  EXPECT_FALSE(other.names_view());
  EXPECT_EQ(other.dither_intensity, 0.0);
  EXPECT_NE(test::import_error(
                write_camera_gltf("", R"("extensions": {"FILMBACK_blender": {"gamma": 7}})"))
                .find("scenes[0].extensions.FILMBACK_blender.gamma: expected a number"),
            std::string::npos);
}

TEST(GltfCamera, BadValuesAreErrorsNamingTheFileAndJsonPath) {
  EXPECT_NE(test::import_error(
                write_camera_gltf(R"("extensions": {"FILMBACK_blender": {"focal_length_mm": -5}})"))
                .find("cameras[0].extensions.FILMBACK_blender.focal_length_mm: expected a number"),
            std::string::npos);
  EXPECT_NE(
      test::import_error(
          write_camera_gltf(R"("extensions": {"FILMBACK_blender": {"sensor_fit": "diagonal"}})"))
          .find("FILMBACK_blender.sensor_fit: 'diagonal', expected auto"),
      std::string::npos);
  EXPECT_NE(
      test::import_error(
          write_camera_gltf(R"("extensions": {"EXT_camera_physical": {"sensorSize": [0.036]}})"))
          .find("EXT_camera_physical.sensorSize: expected [width, height]"),
      std::string::npos);
  EXPECT_NE(test::import_error(
                write_camera_gltf(
                    "", R"("extensions": {"FILMBACK_blender": {"filter_type": "MITCHELL"}})"))
                .find("scenes[0].extensions.FILMBACK_blender.filter_type: 'MITCHELL'"),
            std::string::npos);
  EXPECT_NE(
      test::import_error(
          write_camera_gltf("", R"("extensions": {"FILMBACK_blender": {"shutter_curve": [1]}})"))
          .find("shutter_curve: expected at least two samples"),
      std::string::npos);
}

}  // namespace
}  // namespace fb
