// The shot plan as a table: scenes and options in, plugins, values and their origins out. The plan
// is pure: these tests load no plugin and read no file.
#include "core/render/shot_plan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>

#include "core/util/error.h"

namespace fb {
namespace {

constexpr const char* kFile = "shot.gltf";

ValueOrigin from_shot(const std::string& field) {
  return ValueOrigin::from_file(kFile, "cameras[0].extensions.FILMBACK_blender." + field);
}

// A 50 mm camera 5 m from the origin, each value's origin the scene file; `lens` sets an aperture.
Scene scene_with_camera(bool lens) {
  Scene scene;
  scene.file = kFile;
  SceneCamera camera;
  camera.name = "shot";
  camera.world_from_camera = Transform::translate({0, 0, 5});
  for (size_t v = 0; v < kCameraValueCount; ++v)
    camera.origins[v] = from_shot(camera_value_name(CameraValue(v)));
  if (lens) {
    camera.physical.fstop = 2;
    camera.physical.focus_distance_m = 4;
    camera.physical.aperture_blades = 6;
  }
  scene.cameras.push_back(camera);
  scene.settings.width_px = 64, scene.settings.height_px = 48;
  return scene;
}

std::map<std::string, std::pair<double, std::string>> numbers_of(const PluginChoice& choice) {
  std::map<std::string, std::pair<double, std::string>> out;
  for (const NamedNumber& n : choice.numbers)
    out[n.key] = {n.value, n.origin.text()};
  return out;
}

struct CameraRow {
  const char* what;
  bool lens;
  std::function<void(RenderOptions&)> options;
  const char* plugin;
  const char* origin;  // why that plugin
  std::vector<std::pair<std::string, std::string>> typed;
  std::vector<std::string> number_keys;  // the lens values handed on
};

TEST(ShotPlan, ChoosesTheCameraPluginTheShotNeedsWithEachValuesOrigin) {
  const std::string fstop = std::string(kFile) + ": cameras[0].extensions.FILMBACK_blender.fstop";
  const std::vector<std::string> lens_keys = {"aperture_blades", "aperture_ratio",
                                              "aperture_rotation_rad", "focus_distance_m", "fstop"};
  const std::vector<std::string> no_fstop = {"aperture_blades", "aperture_ratio",
                                             "aperture_rotation_rad", "focus_distance_m"};
  const std::vector<CameraRow> rows = {
      {"pinhole shot", false, [](RenderOptions&) {}, "perspective", fstop.c_str(), {}, {}},
      {"shot with an aperture",
       true,
       [](RenderOptions&) {},
       "thinlens",
       fstop.c_str(),
       {},
       lens_keys},
      {"--fstop on a pinhole shot",
       false,
       [](RenderOptions& o) { o.camera_overrides.fstop = 4; },
       "thinlens",
       "--fstop",
       {},
       lens_keys},
      {"--fstop 0 on a lens shot",
       true,
       [](RenderOptions& o) { o.camera_overrides.fstop = HUGE_VAL; },
       "perspective",
       "--fstop",
       {},
       {}},
      {"--camera-model on a pinhole shot: no f-number to hand on",
       false,
       [](RenderOptions& o) { o.camera_model = "thinlens:fstop=8"; },
       "thinlens",
       "--camera-model",
       {{"fstop", "8"}},
       no_fstop},
      {"--camera-model perspective on a lens shot",
       true,
       [](RenderOptions& o) { o.camera_model = "perspective"; },
       "perspective",
       "--camera-model",
       {},
       lens_keys},
  };
  for (const CameraRow& row : rows) {
    SCOPED_TRACE(row.what);
    RenderOptions options;
    row.options(options);
    const ShotPlan plan = plan_shot(scene_with_camera(row.lens), options);
    EXPECT_EQ(plan.camera_model.name, row.plugin);
    EXPECT_EQ(plan.camera_model.origin.text(), row.origin);
    EXPECT_EQ(plan.camera_model.typed, row.typed);
    std::vector<std::string> keys;
    for (const auto& [key, value] : numbers_of(plan.camera_model))
      keys.push_back(key);
    EXPECT_EQ(keys, row.number_keys);
  }
}

TEST(ShotPlan, LensValuesTravelTypedWithTheirOrigins) {
  RenderOptions options;
  options.camera_overrides.focus_distance_m = 7.25;
  const ShotPlan plan = plan_shot(scene_with_camera(true), options);
  const auto numbers = numbers_of(plan.camera_model);
  // The f-number as itself (the plugin alone makes it a radius), never printed and parsed.
  EXPECT_EQ(numbers.at("fstop"),
            std::pair(2.0, std::string(kFile) + ": cameras[0].extensions.FILMBACK_blender.fstop"));
  EXPECT_EQ(numbers.at("focus_distance_m"), std::pair(7.25, std::string("--focus-distance")));
  EXPECT_EQ(numbers.at("aperture_blades").first, 6);
  EXPECT_EQ(plan.camera_setup().fstop, 2);  // still there for plugins built before parameters
}

// A projection of the scene's own goes to the plugin the table names for it, with its values and
// their origins; a kind no plugin renders is the scene's error, naming where it was read.
TEST(ShotPlan, SceneProjectionsChooseTheirPluginAndHandOnTheirValues) {
  Scene scene = scene_with_camera(false);
  SceneCamera& camera = scene.cameras[0];
  camera.physical.projection = FB_PROJECTION_PANORAMIC;
  camera.model = CameraModel{"fisheye_equidistant",
                             {{"fov_rad", 3.0, from_shot("panorama.fov_rad")}},
                             from_shot("panorama.type")};
  const ShotPlan plan = plan_shot(scene, {});
  EXPECT_EQ(plan.camera_model.name, "fisheye_equidistant");
  EXPECT_EQ(plan.camera_model.origin.text(),
            std::string(kFile) + ": cameras[0].extensions.FILMBACK_blender.panorama.type");
  EXPECT_EQ(numbers_of(plan.camera_model).at("fov_rad").first, 3.0);

  RenderOptions typed;  // a typed camera model still gets the projection's values
  typed.camera_model = "perspective";
  EXPECT_EQ(numbers_of(plan_shot(scene, typed).camera_model).count("fov_rad"), 1u);

  camera.model->kind = "fisheye_made_up";
  try {
    plan_shot(scene, {});
    ADD_FAILURE() << "an unknown projection was planned";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("panorama.type"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'fisheye_made_up'"), std::string::npos) << e.what();
  }
}

TEST(ShotPlan, ShotFilterValuesAreExactAndNameTheirObject) {
  Scene scene = scene_with_camera(false);
  // 0.1 px: 1.5 w = 0.15000000000000002 and w / 4 = 0.025 exactly as computed, no %g rounding.
  scene.settings.filter = PixelFilterSetting{PixelFilterSetting::Type::kGaussian, 0.1,
                                             ValueOrigin::from_file(kFile, "scenes[0].extensions")};
  const ShotPlan plan = plan_shot(scene, {});
  EXPECT_EQ(plan.filter.name, "gaussian");
  const auto numbers = numbers_of(plan.filter);
  EXPECT_EQ(numbers.at("radius").first, 1.5 * 0.1);
  EXPECT_EQ(numbers.at("sigma").first, 0.1 / 4);
  EXPECT_EQ(numbers.at("radius").second, std::string(kFile) + ": scenes[0].extensions");
  EXPECT_EQ(plan.filter.text(), "gaussian:radius=0.15,sigma=0.025");
  EXPECT_EQ(shot_filter_text(scene.settings), plan.filter.text());

  scene.settings.filter->type = PixelFilterSetting::Type::kBox;
  EXPECT_EQ(plan_shot(scene, {}).filter.text(), "box:radius=0.05");
  scene.settings.filter->type = PixelFilterSetting::Type::kBlackmanHarris;
  EXPECT_EQ(plan_shot(scene, {}).filter.text(), "blackman_harris:width=0.1");

  RenderOptions typed;
  typed.filter = "box:radius=2";
  const ShotPlan replaced = plan_shot(scene, typed);
  EXPECT_EQ(replaced.filter.text(), "box:radius=2");
  EXPECT_EQ(replaced.filter.origin.text(), "--filter");
  EXPECT_TRUE(replaced.filter.numbers.empty());
}

TEST(ShotPlan, DefaultsSayTheyAreDefaults) {
  Scene scene = scene_with_camera(false);
  scene.settings.width_px.reset(), scene.settings.height_px.reset();
  scene.cameras[0].intended_aspect = 2.0;
  const ShotPlan plan = plan_shot(scene, {});
  EXPECT_EQ(plan.width_px, kDefaultLongSidePx);
  EXPECT_EQ(plan.height_px, kDefaultLongSidePx / 2);
  EXPECT_EQ(plan.samples_per_pixel, kDefaultSamplesPerPixel);
  EXPECT_EQ(plan.filter.text(), "gaussian");
  EXPECT_EQ(plan.integrator.text(), "path");
  EXPECT_EQ(plan.filter.origin.text().rfind("default", 0), 0u);
  EXPECT_EQ(plan.integrator.origin.text().rfind("default", 0), 0u);
  EXPECT_FALSE(plan.times.shutter_open());
}

TEST(ShotPlan, OptionsReplaceTheShotsTimesAndImage) {
  Scene scene = scene_with_camera(false);
  scene.settings.fps = 25, scene.settings.frame = 50;
  scene.settings.shutter_open_s = -0.01, scene.settings.shutter_close_s = 0.01;
  RenderOptions options;
  options.width = 10, options.height = 20, options.samples_per_pixel = 3;
  options.fps = 50;
  const ShotPlan plan = plan_shot(scene, options);
  EXPECT_EQ(plan.width_px, 10u);
  EXPECT_EQ(plan.height_px, 20u);
  EXPECT_EQ(plan.samples_per_pixel, 3u);
  EXPECT_DOUBLE_EQ(plan.times.frame_s, 1.0);  // frame 50 at 50 fps
  EXPECT_DOUBLE_EQ(plan.times.open_s, 0.99);
  EXPECT_DOUBLE_EQ(plan.times.close_s, 1.01);
  EXPECT_DOUBLE_EQ(plan.sensor.exposure_time_s, 0.02);
}

TEST(ShotPlan, ContradictionsAreUsageErrorsAndBadSceneValuesNameTheFile) {
  RenderOptions half_res;
  half_res.width = 10;
  EXPECT_THROW(plan_shot(scene_with_camera(false), half_res), UsageError);

  RenderOptions physical;
  physical.sensor_model = FB_SENSOR_PHYSICAL;
  EXPECT_THROW(plan_shot(scene_with_camera(false), physical), UsageError);
  EXPECT_NO_THROW(plan_shot(scene_with_camera(true), physical));

  Scene too_close = scene_with_camera(true);
  too_close.cameras[0].physical.focus_distance_m = 0.01;  // inside the 50 mm focal length
  try {
    plan_shot(too_close, {});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  std::string(kFile) + ": cameras[0].extensions.FILMBACK_blender.focus_distance_m"),
              std::string::npos)
        << e.what();
  }

  RenderOptions bad_text;
  bad_text.filter = "gaussian:sigma";
  EXPECT_THROW(plan_shot(scene_with_camera(false), bad_text), UsageError);
}

// Frames 0 and 1 of a lens track; at 24 fps, a half-frame shutter centred on frame 0.5 opens at
// frame 0.25 and closes at 0.75.
Scene scene_with_lens_track() {
  Scene scene = scene_with_camera(true);
  LensTrack track;
  using V = CameraValue;
  track.values[size_t(V::kFocalLength)] = {40, 60};
  track.values[size_t(V::kFocusDistance)] = {2, 6};
  track.values[size_t(V::kFstop)] = {2, 4};
  track.values[size_t(V::kShiftX)] = {0, 0.2};
  scene.cameras[0].lens_track = track;
  scene.settings.fps = 24, scene.settings.frame = 0.5;
  scene.settings.shutter_open_s = -0.25 / 24, scene.settings.shutter_close_s = 0.25 / 24;
  return scene;
}

TEST(ShotPlan, LensTrackIsTheFramesAndAZoomScalesAboutThePrincipalPointWithinTheShutter) {
  const ShotPlan plan = plan_shot(scene_with_lens_track(), {});
  const PhysicalCamera& c = plan.camera.physical;
  EXPECT_DOUBLE_EQ(c.focal_length_mm, 50);
  EXPECT_DOUBLE_EQ(c.focus_distance_m, 4);
  EXPECT_DOUBLE_EQ(c.fstop, 3);
  EXPECT_DOUBLE_EQ(c.shift_x, 0.1);
  // The view plane's extent goes as 1 / f on the same sensor and fit: k = f_centre / f_open.
  ASSERT_TRUE(plan.zoom);
  EXPECT_DOUBLE_EQ(plan.zoom->k_open, 50.0 / 45);
  EXPECT_DOUBLE_EQ(plan.zoom->k_close, 50.0 / 55);
  EXPECT_DOUBLE_EQ(plan.zoom->cx_px, 32 - 0.1 * 64);  // shift: a fraction of the fitted width
  EXPECT_DOUBLE_EQ(plan.zoom->cy_px, 24);
  // Linear from open to the centre and from the centre to close, about the principal point.
  for (const auto& [s, k] : {std::pair{0.0, 50.0 / 45},
                             {0.25, (50.0 / 45 + 1) / 2},
                             {0.5, 1.0},
                             {0.75, (1 + 50.0 / 55) / 2},
                             {1.0, 50.0 / 55}}) {
    float x = 60, y = 4;
    plan.zoom->apply(s, x, y);
    EXPECT_NEAR(x, 25.6 + (60 - 25.6) * k, 1e-5) << "s = " << s;
    EXPECT_NEAR(y, 24 + (4 - 24) * k, 1e-5) << "s = " << s;
  }

  // --focal-length replaces the track: no zoom. A closed shutter: the frame's values, no zoom.
  RenderOptions typed;
  typed.camera_overrides.focal_length_mm = 50;
  EXPECT_FALSE(plan_shot(scene_with_lens_track(), typed).zoom);
  RenderOptions closed;
  closed.shutter_s = Vec2d{0, 0};
  closed.frame = 0.25;
  const ShotPlan still = plan_shot(scene_with_lens_track(), closed);
  EXPECT_FALSE(still.zoom);
  EXPECT_DOUBLE_EQ(still.camera.physical.focal_length_mm, 45);
  // A shutter after the frame (Cycles' START): the focal length at its centre, the rest at the
  // frame (blender/camera.cpp syncs only the field of view at the shutter's times).
  RenderOptions start;
  start.shutter_s = Vec2d{0, 0.25 / 24};
  const ShotPlan later = plan_shot(scene_with_lens_track(), start);
  EXPECT_DOUBLE_EQ(later.camera.physical.focal_length_mm, 52.5);
  EXPECT_DOUBLE_EQ(later.camera.physical.focus_distance_m, 4);
  EXPECT_DOUBLE_EQ(later.zoom->k_open, 52.5 / 50);
}

TEST(ShotPlan, RollingShutterIsTheShotsOrTypedAndOnlyWhileTheShutterIsOpen) {
  Scene scene = scene_with_camera(false);
  scene.settings.shutter_open_s = -0.01, scene.settings.shutter_close_s = 0.01;
  scene.settings.rolling_shutter_duration = 0.2;
  EXPECT_EQ(plan_shot(scene, {}).rolling_shutter->duration, 0.2);
  RenderOptions typed;
  typed.rolling_shutter = RollingShutter{0.5};
  EXPECT_EQ(plan_shot(scene, typed).rolling_shutter->duration, 0.5);
  RenderOptions none;
  none.rolling_shutter = std::optional<RollingShutter>();
  EXPECT_FALSE(plan_shot(scene, none).rolling_shutter);
  RenderOptions closed;
  closed.shutter_s = Vec2d{0, 0};
  EXPECT_FALSE(plan_shot(scene, closed).rolling_shutter);
  closed.rolling_shutter = RollingShutter{0.5};
  EXPECT_THROW(plan_shot(scene, closed), UsageError);
}

TEST(ShotPlan, IsPure) {
  const Scene scene = scene_with_camera(true);
  RenderOptions options;
  options.camera_model = "thinlens:aperture_ratio=2";
  const ShotPlan a = plan_shot(scene, options), b = plan_shot(scene, options);
  EXPECT_EQ(a.camera_model.text(), b.camera_model.text());
  EXPECT_EQ(a.filter.text(), b.filter.text());
  EXPECT_EQ(a.camera_setup().focal_length_mm, b.camera_setup().focal_length_mm);
  // The typed value wins over the shot's of the same name and is said once.
  EXPECT_EQ(a.camera_model.text(),
            "thinlens:aperture_ratio=2,fstop=2,focus_distance_m=4,aperture_blades=6,"
            "aperture_rotation_rad=0");
}

}  // namespace
}  // namespace fb
