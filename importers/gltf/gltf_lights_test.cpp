// Lights and world in Blender's units (docs/blender.md, "Lights and world"): FILMBACK_blender.light
// over KHR_lights_punctual, photometric values converted back, area lights, the uniform world, and
// errors naming the file and JSON path.
#include "importers/gltf/gltf_lights.h"
#include "core/math/constants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "core/accel/render_geometry.h"
#include "core/image/image_io.h"
#include "core/render/light_sampler.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "importers/gltf/gltf_writer.h"
#include "support/gltf_builder.h"
#include "support/import_error.h"

namespace fb {
namespace {

// A file with one node (scaled by `scale`, which lights ignore and area lights take) carrying
// `node_extensions`, an optional KHR light list, and scene extensions.
std::filesystem::path write_lights_gltf(const std::string& node_extensions,
                                        const std::string& khr_lights = "",
                                        const std::string& scene_fields = "", double scale = 1.0) {
  const std::filesystem::path file = test::scratch_dir() / "lights.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"},
  "extensionsUsed": ["FILMBACK_blender", "KHR_lights_punctual"],)"
                      << (khr_lights.empty()
                              ? ""
                              : R"("extensions": {"KHR_lights_punctual": {"lights": [)" +
                                    khr_lights + "]}},")
                      << R"("scene": 0, "scenes": [{"nodes": [0])" << scene_fields << R"(}],
  "nodes": [{"name": "Lamp", "translation": [1, 2, 3], "scale": [)"
                      << scale << "," << scale << "," << scale << R"(],
             "extensions": {)"
                      << node_extensions << "}}]}";
  return file;
}

Scene import_lights(const std::filesystem::path& file, size_t expected_warnings = 0) {
  Diagnostics diagnostics;
  Scene scene = import_gltf(file, diagnostics);
  EXPECT_EQ(diagnostics.count(), expected_warnings);
  return scene;
}

std::string blender_light(const std::string& fields) {
  return R"("FILMBACK_blender": {"light": {)" + fields + "}}";
}

const std::string kLight = "lights.gltf: nodes[0].extensions.FILMBACK_blender.light";

TEST(GltfLights, BlenderPointLightIsPowerOverFourPiAndOverridesTheKhrLight) {
  const Scene scene =
      import_lights(write_lights_gltf(blender_light(R"("type": "POINT", "color": [1, 0.5, 0.25],
                                         "energy_w": 1000, "radius_m": 0.3)") +
                                          R"(, "KHR_lights_punctual": {"light": 0})",
                                      R"({"type": "point", "intensity": 99999})"));
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& light = scene.lights[0];
  EXPECT_EQ(light.type, LightType::kPoint);
  EXPECT_NEAR(light.intensity.x, 1000 / (4 * kPi), 1e-4);
  EXPECT_NEAR(light.intensity.y, 500 / (4 * kPi), 1e-4);
  EXPECT_NEAR(light.intensity.z, 250 / (4 * kPi), 1e-4);
  EXPECT_DOUBLE_EQ(light.radius_m, 0.3);
  EXPECT_EQ(light.name, "Lamp");
  EXPECT_NEAR(light.world_from_light.point({0, 0, 0}).y, 2.0, 1e-12);
}

TEST(GltfLights, KhrIntensitiesAreConvertedBackWithBlendersConstant) {
  // What Blender 3.4 writes for a 1000 W point light and a 3 W/m^2 sun ("Standard" mode).
  const double cd = 1000 / (4 * kPi) * 683, lux = 3 * 683;
  for (const auto& [type, value, expected] :
       {std::tuple{"point", cd, 1000 / (4 * kPi)}, std::tuple{"directional", lux, 3.0}}) {
    const Scene scene = import_lights(write_lights_gltf(
        R"("KHR_lights_punctual": {"light": 0})",
        std::string(R"({"type": ")") + type + R"(", "intensity": )" + std::to_string(value) + "}"));
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_NEAR(scene.lights[0].intensity.x, expected, 1e-6 * expected) << type;
    EXPECT_EQ(scene.lights[0].spot_falloff, SpotFalloff::kGltf);
  }
}

TEST(GltfLights, SpotAndSunKeepBlendersShape) {
  const Scene spot =
      import_lights(write_lights_gltf(blender_light(R"("type": "SPOT", "energy_w": 100,
      "spot_size_rad": 1.2, "spot_blend": 0.4, "radius_m": 0.1)")));
  ASSERT_EQ(spot.lights.size(), 1u);
  EXPECT_EQ(spot.lights[0].type, LightType::kSpot);
  EXPECT_EQ(spot.lights[0].spot_falloff, SpotFalloff::kCycles);
  EXPECT_DOUBLE_EQ(spot.lights[0].spot_outer_angle_rad, 0.6);  // half of the full cone
  EXPECT_DOUBLE_EQ(spot.lights[0].spot_blend, 0.4);
  EXPECT_NEAR(spot.lights[0].intensity.x, 100 / (4 * kPi), 1e-5);

  const Scene sun = import_lights(
      write_lights_gltf(blender_light(R"("type": "SUN", "energy_w": 4.5, "angle_rad": 0.1)")));
  ASSERT_EQ(sun.lights.size(), 1u);
  EXPECT_EQ(sun.lights[0].type, LightType::kDirectional);
  EXPECT_FLOAT_EQ(sun.lights[0].intensity.x, 4.5f);  // irradiance, W/m^2
  EXPECT_DOUBLE_EQ(sun.lights[0].angle_rad, 0.1);
}

TEST(GltfLights, AreaLightsHaveRadiancePowerOverFourAreaAndTheNodesScale) {
  struct Case {
    const char* fields;
    AreaShape shape;
    double size_x, size_y;  // before the node's scale of 2
    double area_m2;         // in the light's own units
    double spread_rad;
  };
  for (const Case& c :
       {Case{R"("shape": "SQUARE", "size_m": 0.5, "size_y_m": 3)", AreaShape::kRectangle, 0.5, 0.5,
             0.25, kPi},
        Case{R"("shape": "RECTANGLE", "size_m": 0.5, "size_y_m": 2, "spread_rad": 0.5)",
             AreaShape::kRectangle, 0.5, 2, 1.0, 0.5},
        // Blender's 180 degrees, pi rounded up to single precision, is read as pi.
        Case{R"("shape": "DISK", "size_m": 1, "spread_rad": 3.1415927410125732)",
             AreaShape::kEllipse, 1, 1, kPi / 4, kPi},
        Case{R"("shape": "ELLIPSE", "size_m": 1, "size_y_m": 0.5, "spread_rad": 1)",
             AreaShape::kEllipse, 1, 0.5, kPi / 8, 1.0}}) {
    const Scene scene = import_lights(write_lights_gltf(
        blender_light(std::string(R"("type": "AREA", "color": [1, 0.5, 0], "energy_w": 300, )") +
                      c.fields),
        "", "", 2.0));
    EXPECT_TRUE(scene.meshes.empty()) << "an area light is not a surface";
    ASSERT_EQ(scene.lights.size(), 1u) << c.fields;
    const Light& light = scene.lights[0];
    EXPECT_EQ(light.type, LightType::kArea);
    EXPECT_EQ(light.area_shape, c.shape) << c.fields;
    EXPECT_DOUBLE_EQ(light.size_x_m, 2 * c.size_x) << c.fields;
    EXPECT_DOUBLE_EQ(light.size_y_m, 2 * c.size_y) << c.fields;
    EXPECT_DOUBLE_EQ(light.spread_rad, c.spread_rad) << c.fields;
    const double world_area = 4 * c.area_m2;
    EXPECT_NEAR(light.intensity.x, 300 / (4 * world_area), 1e-5 * light.intensity.x) << c.fields;
    EXPECT_NEAR(light.intensity.y, 150 / (4 * world_area), 1e-5 * light.intensity.y);
    EXPECT_EQ(light.intensity.z, 0.f);
    // It shines down the node's -Z, placed without the scale.
    EXPECT_NEAR(light.world_from_light.vector({0, 0, -1}).z, -1, 1e-12);
    EXPECT_NEAR(length(light.world_from_light.vector({1, 0, 0})), 1, 1e-12);
  }
}

// Irradiance at `position` on a surface facing `normal`, estimated by the light sampler over a
// stratified grid of all three sample dimensions (light choice and point on it).
double irradiance(const Scene& scene, Vec3f position, Vec3f normal) {
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  constexpr int kChoices = 128, kGrid = 48;
  double sum = 0;
  for (int k = 0; k < kChoices; ++k)
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        const float u[3] = {(k + 0.5f) / kChoices, (i + 0.5f) / kGrid, (j + 0.5f) / kGrid};
        fb_light_sample s;
        if (!sampler.sample(position, u, s) || !(s.pdf > 0.f)) continue;
        const float cosine = dot(normal, Vec3f(s.direction));
        if (cosine > 0.f) sum += double(s.radiance[0]) * cosine / s.pdf;
      }
  return sum / (double(kChoices) * kGrid * kGrid);
}

// The irradiance under an area light's centre, h below it, against the form factors of a disk,
// pi L R^2 / (h^2 + R^2), and of a rectangle (four corner-aligned pieces, Howell's catalogue C-11),
// with Cycles' radiance L = P / (4 A).
TEST(GltfLights, AreaLightIrradianceMatchesTheFormFactor) {
  constexpr double kPower = 100, kHeight = 1.5;
  const Vec3f below(1, 2, float(3 - kHeight)), up(0, 0, 1);
  const Scene disk = import_lights(write_lights_gltf(
      blender_light(R"("type": "AREA", "energy_w": 100, "shape": "DISK", "size_m": 1.2)")));
  const double radius = 0.6;
  const double disk_expected = kPi * kPower / (4 * kPi * radius * radius) * radius * radius /
                               (kHeight * kHeight + radius * radius);
  EXPECT_NEAR(irradiance(disk, below, up), disk_expected, 2e-3 * disk_expected);

  const Scene rect = import_lights(write_lights_gltf(blender_light(
      R"("type": "AREA", "energy_w": 100, "shape": "RECTANGLE", "size_m": 1, "size_y_m": 2)")));
  const double x = 0.5 / kHeight, y = 1.0 / kHeight;
  const double quarter = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                         (2 * kPi);
  const double rect_expected = kPi * kPower / (4 * 2.0) * 4 * quarter;
  EXPECT_NEAR(irradiance(rect, below, up), rect_expected, 2e-3 * rect_expected);
  // One-sided: nothing above the light.
  EXPECT_EQ(irradiance(rect, Vec3f(1, 2, 4), -up), 0.0);
}

// As Cycles' lights, an area light is not a surface: no ray hits it or is shadowed by it, and BSDF
// rays find it (LightSampler::crossed) only from the side it shines to.
TEST(GltfLights, AreaLightsAreFoundByRaysOnlyFromTheirLitSide) {
  const Scene scene = import_lights(write_lights_gltf(
      blender_light(R"("type": "AREA", "energy_w": 100, "shape": "SQUARE", "size_m": 1)")));
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  const auto ray = [](float from_z, float dz) {
    fb_ray r{};
    r.origin[0] = 1, r.origin[1] = 2, r.origin[2] = from_z;
    r.direction[2] = dz;
    r.t_max = HUGE_VALF;
    return r;
  };
  const fb_ray from_below = ray(1, 1), from_above = ray(5, -1);
  fb_hit hit;
  EXPECT_FALSE(geometry.intersect(from_below, hit));
  EXPECT_FALSE(geometry.occluded(from_below));
  fb_light_crossing crossings[4];
  ASSERT_EQ(sampler.crossed(from_below, HUGE_VALF, crossings, 4), 1u);
  EXPECT_NEAR(crossings[0].t, 2.f, 1e-5f);
  EXPECT_NEAR(crossings[0].radiance[0], 100 / 4.f, 1e-4f);
  EXPECT_EQ(sampler.crossed(from_below, 1.5f, crossings, 4), 0u);  // a surface before it
  EXPECT_EQ(sampler.crossed(from_above, HUGE_VALF, crossings, 4), 0u);
}

// `filmback convert` writes an area light into our extension (KHR_lights_punctual has none), and
// reading it back gives the same light.
TEST(GltfLights, AreaLightsSurviveConvert) {
  const Scene scene = import_lights(
      write_lights_gltf(blender_light(R"("type": "AREA", "energy_w": 100, "color": [1, 0.5, 0.25],
                       "shape": "ELLIPSE", "size_m": 1.5, "size_y_m": 0.5, "spread_rad": 0.7)"),
                        "", "", 2.0));
  const std::filesystem::path written = test::scratch_dir() / "converted.gltf";
  Diagnostics diagnostics;
  fb::write_gltf(scene, written, diagnostics);
  EXPECT_EQ(diagnostics.count(), 0u);
  const Scene back = import_lights(written);
  ASSERT_EQ(back.lights.size(), 1u);
  const Light &a = scene.lights[0], &b = back.lights[0];
  EXPECT_EQ(b.type, LightType::kArea);
  EXPECT_EQ(b.area_shape, AreaShape::kEllipse);
  EXPECT_NEAR(b.size_x_m, a.size_x_m, 1e-6);
  EXPECT_NEAR(b.size_y_m, a.size_y_m, 1e-6);
  EXPECT_NEAR(b.spread_rad, a.spread_rad, 1e-6);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(b.intensity[c], a.intensity[c], 1e-5 * a.intensity.x);
  EXPECT_NEAR(b.world_from_light.point({0, 0, 0}).z, 3, 1e-9);
}

TEST(GltfLights, WorldColourTimesStrengthIsTheBackground) {
  const Scene ours = import_lights(write_lights_gltf(
      "", "",
      R"(, "extensions": {"FILMBACK_blender": {"world_color": [0.2, 0.4, 0.8], "world_strength": 2.5}})"));
  EXPECT_FLOAT_EQ(ours.background.x, 0.5f);
  EXPECT_FLOAT_EQ(ours.background.y, 1.0f);
  EXPECT_FLOAT_EQ(ours.background.z, 2.0f);
  const Scene extras = import_lights(write_lights_gltf(
      "", "", R"(, "extras": {"world_color": [1, 1, 1], "world_strength": 0.25})"));
  EXPECT_FLOAT_EQ(extras.background.y, 0.25f);
}

// world_hdr_uri: an image beside the file, times world_strength; paths out of the scene's
// folder, missing files and pixels that are not radiance are errors.
TEST(GltfLights, WorldImageIsReadBesideTheFile) {
  const auto with_image = [](const std::string& uri, float texel) {
    const std::filesystem::path file = write_lights_gltf("", "",
                                                         R"(, "extensions": {"FILMBACK_blender": {
        "world_color": [1, 1, 1], "world_strength": 2, "world_hdr_uri": ")" +
                                                             uri + R"("}})");
    const Image image{4, 2, {"R", "G", "B"}, std::vector<float>(24, 0.5f)};
    Image changed = image;
    changed.pixels[3 * 5 + 1] = texel;  // pixel (1, 1), green
    write_images(changed, {file.parent_path() / "sky.exr"}, {});
    return file;
  };
  const Scene scene = import_lights(with_image("sky.exr", 3.f));
  ASSERT_TRUE(scene.environment.has_value());
  EXPECT_EQ(scene.environment->width, 4u);
  EXPECT_EQ(scene.environment->height, 2u);
  EXPECT_FLOAT_EQ(scene.environment->texels[5].y, 6.f);
  EXPECT_FLOAT_EQ(scene.environment->texels[0].x, 1.f);

  const std::string where = "lights.gltf: scenes[0].extensions.FILMBACK_blender.world_hdr_uri: ";
  for (const auto& [uri, texel, expected] :
       {std::tuple{std::string("../sky.exr"), 1.f, "outside the scene's folder"},
        std::tuple{std::string("missing.exr"), 1.f, "not found"},
        std::tuple{std::string("/etc/passwd"), 1.f, "relative to the scene's folder"},
        std::tuple{std::string("sky.exr"), -1.f, "negative or not finite"},
        std::tuple{std::string("sky.exr"), NAN, "negative or not finite"}}) {
    const std::string error = test::import_error(with_image(uri, texel));
    EXPECT_NE(error.find(where), std::string::npos) << uri << "\n" << error;
    EXPECT_NE(error.find(expected), std::string::npos) << uri << "\n" << error;
  }
}

TEST(GltfLights, BadValuesAreErrorsNamingTheFileAndJsonPath) {
  const struct {
    std::string light, path, expected;
  } cases[] = {
      {R"("type": "HEMI", "energy_w": 1)", ".type", "not a light type"},
      {R"("energy_w": 1)", "", "expected a type"},
      {R"("type": "POINT")", ".energy_w", "power in W"},
      {R"("type": "POINT", "energy_w": -5)", ".energy_w", "expected a number in [0, "},
      {R"("type": "POINT", "energy_w": "bright")", ".energy_w", "expected a number"},
      {R"("type": "POINT", "energy_w": 1, "color": [1, -1, 0])", ".color[1]",
       "expected a number in [0, "},
      {R"("type": "POINT", "energy_w": 1, "color": [1, 1])", ".color", "three"},
      {R"("type": "POINT", "energy_w": 1, "radius_m": -0.1)", ".radius_m", "[0, "},
      {R"("type": "SPOT", "energy_w": 1, "spot_size_rad": 4)", ".spot_size_rad", "number in"},
      {R"("type": "SPOT", "energy_w": 1, "spot_blend": 1.5)", ".spot_blend", "[0, 1]"},
      {R"("type": "SUN", "energy_w": 1, "angle_rad": -1)", ".angle_rad", "number in"},
      {R"("type": "AREA", "energy_w": 1, "shape": "STAR")", ".shape", "not an area light shape"},
      {R"("type": "AREA", "energy_w": 1, "size_m": 0)", ".size_m", "number in"},
      {R"("type": "AREA", "energy_w": 1, "shape": "RECTANGLE", "size_y_m": -2)", ".size_y_m",
       "number in"},
      {R"("type": "AREA", "energy_w": 1, "spread_rad": 4)", ".spread_rad", "number in"},
      {R"("type": "AREA", "energy_w": 1, "spread_rad": "wide")", ".spread_rad", "a number"},
      {R"("type": "AREA", "energy_w": 1e30, "size_m": 1e-6)", "", "overflows"},
      {R"("type": "POINT", "energy_w": 1, "use_nodes": 1)", ".use_nodes", "true or false"},
  };
  for (const auto& c : cases) {
    const std::string error = test::import_error(write_lights_gltf(blender_light(c.light)));
    EXPECT_NE(error.find(kLight + c.path + ": "), std::string::npos) << c.light << "\n" << error;
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.light << "\n" << error;
  }
  const std::string world = test::import_error(
      write_lights_gltf("", "", R"(, "extensions": {"FILMBACK_blender": {"world_strength": -1}})"));
  EXPECT_NE(world.find("lights.gltf: scenes[0].extensions.FILMBACK_blender.world_strength: "),
            std::string::npos)
      << world;
  const std::string khr = test::import_error(write_lights_gltf(
      R"("KHR_lights_punctual": {"light": 3})", R"({"type": "point", "intensity": 1})"));
  EXPECT_NE(khr.find("lights.gltf: nodes[0].extensions.KHR_lights_punctual.light: "),
            std::string::npos)
      << khr;
}

TEST(GltfLights, ANodeTreeIsReportedAsNotCarried) {
  const Scene scene = import_lights(
      write_lights_gltf(blender_light(R"("type": "POINT", "energy_w": 10, "use_nodes": true)")), 1);
  EXPECT_EQ(scene.lights.size(), 1u);
}

}  // namespace
}  // namespace fb
