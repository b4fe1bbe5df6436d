// FILMBACK_povray (docs/pov.md "Conversion"): POV-Ray's lights and pigments written by
// `filmback convert` read back exactly, bad values are errors naming the JSON path, and what
// other viewers read in its place (mean colours, specular levels) is what filmback shows.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "core/math/constants.h"
#include "core/texture/solid_pattern.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "importers/gltf/gltf_povray_pattern.h"
#include "importers/gltf/gltf_writer.h"
#include "support/gltf_builder.h"
#include "support/povray_light.h"
#include "support/written_gltf.h"

namespace fb {
namespace {

Scene round_trip(const Scene& scene, const std::string& name) {
  const std::filesystem::path file = test::scratch_dir() / name;
  Diagnostics diagnostics;
  write_gltf(scene, file, diagnostics);
  return import_gltf(file, diagnostics);
}

Light pov_light(LightType type, Vec3d position) {
  return test::povray_light(
      type, Transform::translate(position) * Transform::rotate({0.1, 0.7, -0.2, 0.6}));
}

void expect_same_light(const Light& a, const Light& b) {
  EXPECT_EQ(a.type, b.type);
  EXPECT_EQ(a.intensity.x, b.intensity.x);
  EXPECT_EQ(a.intensity.y, b.intensity.y);
  EXPECT_EQ(a.intensity.z, b.intensity.z);
  EXPECT_EQ(a.decay, b.decay);
  EXPECT_EQ(a.fade_distance_m, b.fade_distance_m);
  EXPECT_EQ(a.fade_power, b.fade_power);
  if (a.type == LightType::kSpot) {
    EXPECT_EQ(a.spot_falloff, b.spot_falloff);
    EXPECT_EQ(a.spot_inner_angle_rad, b.spot_inner_angle_rad);
    EXPECT_EQ(a.spot_outer_angle_rad, b.spot_outer_angle_rad);
    EXPECT_EQ(a.spot_tightness, b.spot_tightness);
  }
  EXPECT_EQ(a.casts_shadows, b.casts_shadows);
  EXPECT_EQ(a.area_size1, b.area_size1);
  EXPECT_EQ(a.area_size2, b.area_size2);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.area_axis1[i], b.area_axis1[i]);
    EXPECT_EQ(a.area_axis2[i], b.area_axis2[i]);
  }
  EXPECT_EQ(a.area_circular, b.area_circular);
  EXPECT_EQ(a.area_orient, b.area_orient);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(a.world_from_light(r, c), b.world_from_light(r, c), 1e-12);
}

TEST(GltfPovray, LightsReadBackExactly) {
  Scene scene;
  Light point = pov_light(LightType::kPoint, {1, 2, 3});
  point.fade_distance_m = 2.5, point.fade_power = 1.7;
  Light spot = pov_light(LightType::kSpot, {-1, 4, 0});
  spot.spot_falloff = SpotFalloff::kPov;
  spot.spot_inner_angle_rad = 0.2, spot.spot_outer_angle_rad = 0.45, spot.spot_tightness = 7;
  // Wider than glTF's spots go (a half-angle above pi/2): only KHR's approximation is clamped.
  Light wide = spot;
  wide.spot_inner_angle_rad = 1.2, wide.spot_outer_angle_rad = 2.0;
  Light parallel = pov_light(LightType::kDirectional, {0, 10, 0});
  parallel.casts_shadows = false;
  Light area = pov_light(LightType::kPoint, {3, 3, -2});
  area.area_axis1 = {0.5, 0, 0.1}, area.area_axis2 = {0, 0.3, 0};
  area.area_size1 = 5, area.area_size2 = 3;
  area.area_circular = area.area_orient = true;
  scene.lights = {point, spot, wide, parallel, area};
  const Scene back = round_trip(scene, "lights.gltf");
  ASSERT_EQ(back.lights.size(), scene.lights.size());
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    SCOPED_TRACE(i);
    expect_same_light(scene.lights[i], back.lights[i]);
  }
}

void expect_same_colour(const SolidColour& a, const SolidColour& b) {
  EXPECT_EQ(a.rgb.x, b.rgb.x);
  EXPECT_EQ(a.rgb.y, b.rgb.y);
  EXPECT_EQ(a.rgb.z, b.rgb.z);
  EXPECT_EQ(a.filter, b.filter);
  EXPECT_EQ(a.transmit, b.transmit);
}

void expect_same_pattern(const SolidPattern& a, const SolidPattern& b) {
  EXPECT_EQ(a.kind, b.kind);
  expect_same_colour(a.colour, b.colour);
  ASSERT_EQ(a.colour_map.size(), b.colour_map.size());
  for (size_t i = 0; i < a.colour_map.size(); ++i) {
    EXPECT_EQ(a.colour_map[i].value, b.colour_map[i].value);
    expect_same_colour(a.colour_map[i].colour, b.colour_map[i].colour);
  }
  ASSERT_EQ(a.list.size(), b.list.size());
  for (size_t i = 0; i < a.list.size(); ++i)
    expect_same_pattern(a.list[i], b.list[i]);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      EXPECT_EQ(a.pattern_from_world(r, c), b.pattern_from_world(r, c));
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.turbulence[i], b.turbulence[i]);
    EXPECT_EQ(a.gradient[i], b.gradient[i]);
    EXPECT_EQ(a.brick_size[i], b.brick_size[i]);
  }
  EXPECT_EQ(a.octaves, b.octaves);
  EXPECT_EQ(a.omega, b.omega);
  EXPECT_EQ(a.lambda, b.lambda);
  EXPECT_EQ(a.frequency, b.frequency);
  EXPECT_EQ(a.phase, b.phase);
  EXPECT_EQ(a.wave, b.wave);
  EXPECT_EQ(a.wave_exponent, b.wave_exponent);
  EXPECT_EQ(a.mortar, b.mortar);
  EXPECT_EQ(a.spiral_arms, b.spiral_arms);
  EXPECT_EQ(a.agate_turbulence, b.agate_turbulence);
}

SolidPattern solid(Rgb rgb, float filter = 0, float transmit = 0) {
  SolidPattern p;
  p.colour = {rgb, filter, transmit};
  return p;
}

// Every field away from its default somewhere in the tree.
SolidPattern every_field() {
  SolidPattern marble;
  marble.kind = SolidPatternKind::kMarble;
  marble.colour_map = {{0.f, {{0.1f, 0.2f, 0.3f}, 0.f, 0.f}},
                       {0.625f, {{0.9f, 0.8f, 0.7f}, 0.25f, 0.f}},
                       {1.f, {{2.f, 1.5f, 0.f}, 0.f, 0.5f}}};
  marble.turbulence = {0.3, 0.4, 0.5};
  marble.octaves = 4, marble.omega = 0.6, marble.lambda = 2.5;
  marble.frequency = 3, marble.phase = 0.123, marble.wave = SolidWave::kSine;
  marble.pattern_from_world = Transform::scale({2, 1, 0.5}) * Transform::translate({0.1, -3, 7});
  SolidPattern gradient;
  gradient.kind = SolidPatternKind::kGradient;
  gradient.gradient = {0.6, 0, 0.8};
  gradient.wave = SolidWave::kPoly, gradient.wave_exponent = 2.5;
  SolidPattern spiral;
  spiral.kind = SolidPatternKind::kSpiral1;
  spiral.spiral_arms = 3;
  SolidPattern hexagon;
  hexagon.kind = SolidPatternKind::kHexagon;
  hexagon.list = {solid({0.2f, 0.4f, 0.6f}, 0.1f, 0.2f), gradient, spiral};
  SolidPattern brick;
  brick.kind = SolidPatternKind::kBrick;
  brick.brick_size = {2, 1, 1.5}, brick.mortar = 0.2;
  SolidPattern agate;
  agate.kind = SolidPatternKind::kAgate;
  agate.agate_turbulence = 0.75;
  SolidPattern checker;
  checker.kind = SolidPatternKind::kChecker;
  checker.list = {marble, hexagon};
  checker.pattern_from_world = Transform::rotate({0.3, 0.1, 0.2, 0.9});
  SolidPattern outer;
  outer.kind = SolidPatternKind::kChecker;
  outer.list = {checker, brick};
  // One more level, for the other kinds: the checker's second entry's own list.
  outer.list[1].list = {agate, solid({1, 1, 1})};
  return outer;
}

// A viewer without FILMBACK_povray gets a pattern's mean colour: the colours the renderer shows,
// POV-Ray's defaults included (a radial without a map is cyan, yellow and magenta, a checker
// without colours blue and green), against the mean of evaluate_solid over points spread evenly
// in angle about y (radial's value) and in checker cells.
TEST(GltfPovray, ViewersGetTheMeanOfWhatTheRendererShows) {
  SolidPattern radial;
  radial.kind = SolidPatternKind::kRadial;
  SolidPattern bare_checker;
  bare_checker.kind = SolidPatternKind::kChecker;
  SolidPattern checker = bare_checker;
  checker.list = {solid({1, 0, 0}), radial};
  for (const SolidPattern& p : {radial, bare_checker, checker}) {
    SCOPED_TRACE(int(p.kind));
    constexpr int kPoints = 40000;
    Rgb sum;
    for (int i = 0; i < kPoints; ++i) {
      // Additive recurrences (irrational steps): angle, radius and height evenly spread.
      const double u = std::fmod(i * 0.6180339887, 1.0), v = std::fmod(i * 0.7548776662, 1.0),
                   w = std::fmod(i * 0.5698402910, 1.0);
      const double angle = 2 * kPi * u, radius = 1 + 49 * v;
      sum +=
          evaluate_solid(p, {radius * std::cos(angle), 100 * w - 50, radius * std::sin(angle)}).rgb;
    }
    const Rgb mean = gltf::mean_colour(p).rgb;
    EXPECT_NEAR(mean.x, sum.x / kPoints, 0.01);
    EXPECT_NEAR(mean.y, sum.y / kPoints, 0.01);
    EXPECT_NEAR(mean.z, sum.z / kPoints, 0.01);
  }
}

TEST(GltfPovray, PigmentsReadBackExactly) {
  Scene scene;
  Material m;
  m.name = "pigment";
  m.base_color = {1.3f, 0.7f, 0.7f};  // diffuse times a colour: beyond glTF's [0, 1]
  m.base_color_pattern = every_field();
  m.alpha_mode = AlphaMode::kBlend;   // the pattern's transmit lowers the coverage
  m.emission = {2.5f, 0.5f, 0.125f};  // times the pattern at the hit; emissiveFactor is a mean
  scene.materials = {m, Material()};
  const Scene back = round_trip(scene, "pigment.gltf");
  ASSERT_EQ(back.materials.size(), 2u);
  const Material& b = back.materials[0];
  EXPECT_EQ(b.base_color.x, 1.3f);
  EXPECT_EQ(b.base_color.y, 0.7f);
  ASSERT_TRUE(b.base_color_pattern);
  expect_same_pattern(*m.base_color_pattern, *b.base_color_pattern);
  EXPECT_EQ(b.alpha_mode, AlphaMode::kBlend);
  EXPECT_EQ(b.emission.x, 2.5f);
  EXPECT_EQ(b.emission.y, 0.5f);
  EXPECT_EQ(b.emission.z, 0.125f);
  EXPECT_FALSE(back.materials[1].base_color_pattern);
}

// The written file with the last `from` replaced by `to`, read back: the error's text.
std::string error_after(const Scene& scene, const std::string& from, const std::string& to) {
  const std::filesystem::path file = test::scratch_dir() / "edited.gltf";
  Diagnostics diagnostics;
  write_gltf(scene, file, diagnostics);
  std::stringstream text;
  text << std::ifstream(file).rdbuf();
  std::string json = text.str();
  const size_t at = json.rfind(from);  // the last: past KHR_lights_punctual, deepest in a tree
  if (at == std::string::npos) return "'" + from + "' not in the file";
  json.replace(at, from.size(), to);
  std::ofstream(file) << json;
  try {
    import_gltf(file, diagnostics);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// A viewer that knows only standard glTF gets a finish's specular level from what it reads:
// Blender 3.4 sets Principled Specular = lum(specularColorFactor) F0(ior) / 0.08 (F0 = 0.08
// Specular) and ignores specularFactor, a viewer that follows KHR_materials_specular has F0 =
// F0(ior) specularColorFactor specularFactor. filmback reads back the exact factor.
TEST(GltfPovray, SpecularLevelsReachOtherViewersAndReadBackExactly) {
  Scene scene;
  Material lambertian, highlight, glass, glossy;
  lambertian.specular = 0.f;
  highlight.specular = 0.5f;
  glass.specular = 0.5f, glass.transmission = 1.f, glass.ior = 1.33f;
  scene.materials = {lambertian, highlight, glass, glossy};
  const std::filesystem::path file = test::scratch_dir() / "specular_levels.gltf";
  const tinygltf::Model model = test::written_gltf(scene, file);
  ASSERT_EQ(model.materials.size(), 4u);

  // The F0 each reading gives, at glTF's default ior 1.5 (F0 0.04).
  const auto khr = [&](size_t i, const char* key, double absent) {
    const auto& ext = model.materials[i].extensions;
    const auto it = ext.find("KHR_materials_specular");
    if (it == ext.end() || !it->second.Has(key)) return absent;
    const tinygltf::Value& v = it->second.Get(key);
    return v.IsArray() ? v.Get(1).GetNumberAsDouble() : v.GetNumberAsDouble();
  };
  const auto blender_f0 = [&](size_t i) { return khr(i, "specularColorFactor", 1) * 0.04; };
  const auto khr_f0 = [&](size_t i) {
    return khr(i, "specularColorFactor", 1) * khr(i, "specularFactor", 1) * 0.04;
  };
  for (size_t i : {size_t(0), size_t(1), size_t(3)}) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(blender_f0(i), scene.materials[i].specular * 0.04, 1e-7);
    EXPECT_NEAR(khr_f0(i), scene.materials[i].specular * 0.04, 1e-7);
  }
  // Lambertian: no layer at grazing angles either (F90 = specularFactor).
  EXPECT_EQ(khr(0, "specularFactor", 1), 0);
  // Glass keeps specularFactor: its ior also sets refraction.
  EXPECT_EQ(khr(2, "specularFactor", 1), 0.5);
  EXPECT_EQ(khr(2, "specularColorFactor", 1), 1);

  Diagnostics diagnostics;
  const Scene back = import_gltf(file, diagnostics);
  ASSERT_EQ(back.materials.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(back.materials[i].specular, scene.materials[i].specular);
    EXPECT_EQ(back.materials[i].ior, scene.materials[i].ior);
  }
  const std::string e = error_after(scene, "\"specular_factor\": 0.5", "\"specular_factor\": 1.5");
  EXPECT_NE(e.find("materials[1].extensions.FILMBACK_povray.specular_factor: expected a number "
                   "in [0, 1]"),
            std::string::npos)
      << e;
}

Scene with_pattern(SolidPattern p) {
  Scene scene;
  Material m;
  m.base_color_pattern = std::move(p);
  scene.materials = {m};
  return scene;
}

TEST(GltfPovray, BadPigmentsNameTheirJsonPath) {
  const Scene scene = with_pattern(every_field());
  const std::string pigment = "materials[0].extensions.FILMBACK_povray.pigment";
  std::string e = error_after(scene, "\"agate\"", "\"plaid\"");
  EXPECT_NE(e.find(pigment + ".list[1].list[0].pattern: 'plaid' is not one of"), std::string::npos)
      << e;
  e = error_after(scene, "\"value\": 0.625", "\"value\": 1.5");
  EXPECT_NE(e.find(pigment + ".list[0].list[0].colour_map[1].value: expected a number in [0, 1]"),
            std::string::npos)
      << e;
  e = error_after(scene, "\"octaves\": 4", "\"octaves\": 4.5");
  EXPECT_NE(e.find(pigment + ".list[0].list[0].octaves: expected a whole number"),
            std::string::npos)
      << e;
  e = error_after(scene, "\"wave\": \"sine\"", "\"wave\": \"square\"");
  EXPECT_NE(e.find(pigment + ".list[0].list[0].wave: 'square' is not one of"), std::string::npos)
      << e;
  e = error_after(scene, "\"pattern_from_world\": [", "\"pattern_from_world\": [1, ");
  EXPECT_NE(e.find(pigment + ".list[0].pattern_from_world: expected an array of at most 16"),
            std::string::npos)
      << e;
  e = error_after(scene, "\"filter\": 0.25", "\"filter\": -0.25");
  EXPECT_NE(e.find(pigment + ".list[0].list[0].colour_map[1].filter: expected a number in [0, 1]"),
            std::string::npos)
      << e;

  // Nesting and size are bounded: a stack of 17 checkers, and 3^7 hexagon leaves.
  SolidPattern deep = solid({1, 0, 0});
  for (int i = 0; i < 17; ++i) {
    SolidPattern checker;
    checker.kind = SolidPatternKind::kChecker;
    checker.list = {deep, solid({0, 0, 1})};
    deep = checker;
  }
  e = error_after(with_pattern(deep), "\"pattern\": \"solid\"", "\"pattern\": \"solid\"");
  EXPECT_NE(e.find(": list patterns nested deeper than 16"), std::string::npos) << e;
  SolidPattern wide = solid({1, 0, 0});
  for (int i = 0; i < 7; ++i) {
    SolidPattern hexagon;
    hexagon.kind = SolidPatternKind::kHexagon;
    hexagon.list = {wide, wide, wide};
    wide = hexagon;
  }
  e = error_after(with_pattern(wide), "\"pattern\": \"solid\"", "\"pattern\": \"solid\"");
  EXPECT_NE(e.find(": more than 1024 patterns in one pigment"), std::string::npos) << e;
}

TEST(GltfPovray, BadLightsNameTheirJsonPath) {
  Scene scene;
  Light area = pov_light(LightType::kPoint, {0, 0, 0});
  area.area_axis1 = {1, 0, 0}, area.area_axis2 = {0, 1, 0};
  area.area_size1 = 2, area.area_size2 = 3;
  scene.lights = {area};
  const std::string light = "nodes[0].extensions.FILMBACK_povray.light";
  std::string e = error_after(scene, "\"size1\": 2", "\"size1\": 0");
  EXPECT_NE(e.find(light + ".area_light.size1: expected a whole number in [1, 4096]"),
            std::string::npos)
      << e;
  e = error_after(scene, "\"type\": \"point\"", "\"type\": \"sun\"");
  EXPECT_NE(e.find(light + ".type: expected point, spot or parallel"), std::string::npos) << e;
  e = error_after(scene, "\"axis1\": [", "\"axis1\": [7, ");
  EXPECT_NE(e.find(light + ".area_light.axis1: expected"), std::string::npos) << e;
}

}  // namespace
}  // namespace fb
