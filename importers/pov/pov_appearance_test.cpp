#include "importers/pov/pov_appearance.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include "core/shading/gltf_bsdf.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>

#include "core/math/constants.h"
#include "core/render/environment.h"
#include "core/render/light_sampler.h"
#include "core/render/render_job.h"
#include "core/texture/solid_pattern.h"
#include "importers/gltf/gltf_importer.h"
#include "importers/pov/pov_importer.h"
#include "importers/pov/pov_space.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"
#include "support/povray_render.h"

namespace fb::pov {
namespace {

Texture plain_texture(Colour colour, double diffuse) {
  Texture t;
  t.pigment.colour = colour;
  t.finish.diffuse = diffuse;
  t.where = {"scene.pov", 3, 1};
  return t;
}

TEST(PovAppearance, DefaultFinishIsLambertianWithAlbedoPigmentTimesDiffuse) {
  const Material m = make_material(plain_texture({0.8, 0.5, 0.2}, 0.6), {}, 1.0, {1, 1, 1});
  EXPECT_NEAR(m.base_color.x, 0.48, 1e-6);
  EXPECT_NEAR(m.base_color.y, 0.30, 1e-6);
  EXPECT_NEAR(m.base_color.z, 0.12, 1e-6);
  EXPECT_EQ(m.specular, 0.f);  // no Fresnel layer: exactly Lambertian
  EXPECT_EQ(m.metallic, 0.f);
  EXPECT_EQ(m.transmission, 0.f);
  EXPECT_EQ(m.emission.x, 0.f);  // the default ambient 0.1 is left to the path tracer
  EXPECT_EQ(m.alpha_mode, AlphaMode::kOpaque);
  EXPECT_FALSE(m.base_color_pattern);
}

TEST(PovAppearance, SelfLitFinishesBecomeEmission) {
  Texture marker = plain_texture({1, 0.5, 0}, 0);
  marker.finish.ambient = {1, 1, 1};
  Material m = make_material(marker, {}, 1.0, {1, 1, 1});
  EXPECT_FLOAT_EQ(m.emission.x, 1.f);
  EXPECT_FLOAT_EQ(m.emission.y, 0.5f);
  EXPECT_EQ(m.base_color.x, 0.f);
  m = make_material(marker, {}, 1.0, {0.5, 0.5, 0.5});  // global ambient_light scales it
  EXPECT_FLOAT_EQ(m.emission.x, 0.5f);

  Texture emissive = plain_texture({0.2, 0.4, 0.6}, 0.6);
  emissive.finish.emission = {1, 1, 1};
  m = make_material(emissive, {}, 1.0, {1, 1, 1});
  EXPECT_FLOAT_EQ(m.emission.z, 0.6f);
  EXPECT_NEAR(m.base_color.z, 0.36, 1e-6);  // and still diffuse
}

TEST(PovAppearance, AssumedGammaDecodesColoursLegacyScenesAsDisplayValues) {
  Scene scene;
  EXPECT_EQ(colour_gamma(scene), 1.0);  // #version 3.7
  scene.version = 3.6;
  EXPECT_EQ(colour_gamma(scene), 2.2);
  scene.assumed_gamma = 1.8;
  EXPECT_EQ(colour_gamma(scene), 1.8);
  const Material m = make_material(plain_texture({0.5, 0.5, 0.5}, 1), {}, 2.2, {1, 1, 1});
  EXPECT_NEAR(m.base_color.x, std::pow(0.5, 2.2), 1e-6);
}

TEST(PovAppearance, IdenticalTexturesShareOneMaterial) {
  Scene scene;
  fb::Scene out;
  Diagnostics diagnostics;
  MaterialTable table(scene, out, diagnostics);
  Texture a = plain_texture({1, 0, 0}, 0.6), b = a, c = plain_texture({0, 1, 0}, 0.6);
  b.where.line = 40;  // written elsewhere, the same content
  EXPECT_EQ(table.material(a, {}), 0u);
  EXPECT_EQ(table.material(b, {}), 0u);
  EXPECT_EQ(table.material(c, {}), 1u);
  Interior refracting;
  refracting.ior = 1.5;
  EXPECT_EQ(table.material(a, refracting), 0u);  // an opaque surface's interior is unseen
  const Texture glassy = plain_texture({1, 1, 1, 0.5, 0}, 0.6);
  EXPECT_EQ(table.material(glassy, {}), 2u);
  EXPECT_EQ(table.material(glassy, refracting), 3u);  // refracting: another material
  EXPECT_EQ(out.materials.size(), 4u);
  EXPECT_EQ(out.materials[0].name, "scene.pov:3:1");
  a.finish.brilliance = 2;
  table.material(a, {});
  c.finish.brilliance = 3;
  table.material(c, {});
  ASSERT_EQ(diagnostics.count(), 1u);  // reported once, with where it was first met
  EXPECT_NE(diagnostics.messages()[0].find("scene.pov:3:1: finish brilliance"), std::string::npos);
}

TEST(PovAppearance, FilterIsTransmissionTransmitIsCoverageAndIorMakesGlass) {
  Material m = make_material(plain_texture({1, 1, 1, 0.6, 0}, 0.6), {}, 1.0, {1, 1, 1});
  EXPECT_FLOAT_EQ(m.transmission, 0.6f);
  EXPECT_EQ(m.alpha_mode, AlphaMode::kOpaque);
  m = make_material(plain_texture({1, 1, 1, 0, 0.3}, 0.6), {}, 1.0, {1, 1, 1});
  EXPECT_EQ(m.transmission, 0.f);
  EXPECT_EQ(m.alpha_mode, AlphaMode::kBlend);
  EXPECT_FLOAT_EQ(m.alpha, 0.7f);
  Interior glass;
  glass.ior = 1.5;
  m = make_material(plain_texture({0.9, 1, 0.9, 0, 0.9}, 0.1), glass, 1.0, {1, 1, 1});
  EXPECT_FLOAT_EQ(m.transmission, 0.9f);
  EXPECT_FLOAT_EQ(m.ior, 1.5f);
  EXPECT_EQ(m.alpha_mode, AlphaMode::kOpaque);  // refracted, not seen through
  EXPECT_EQ(m.specular, 1.f);
  EXPECT_LE(m.roughness, 0.15f);
}

TEST(PovAppearance, ReflectionAndHighlightsBecomeTheSpecularLayer) {
  Texture mirror = plain_texture({0.5, 0.5, 0.5}, 0.2);
  mirror.finish.reflection_min = mirror.finish.reflection_max = {0.36, 0.36, 0.36};
  Material m = make_material(mirror, {}, 1.0, {1, 1, 1});
  const double f0 = std::pow((m.ior - 1) / (m.ior + 1), 2);
  EXPECT_NEAR(f0, 0.36, 1e-5);  // Fresnel's reflectance at normal incidence is POV-Ray's
  EXPECT_EQ(m.roughness, 0.f);
  mirror.finish.metallic = 1;
  m = make_material(mirror, {}, 1.0, {1, 1, 1});
  EXPECT_FLOAT_EQ(m.metallic, 0.36f);

  Texture shiny = plain_texture({0.5, 0.5, 0.5}, 0.6);
  shiny.finish.phong = 1, shiny.finish.phong_size = 40;
  m = make_material(shiny, {}, 1.0, {1, 1, 1});
  // Phong exponent 40 ~ Blinn 160 ~ GGX alpha sqrt(2 / 162) (Walter et al. 2007).
  EXPECT_NEAR(m.roughness * m.roughness, std::sqrt(2.0 / 162), 1e-6);
  EXPECT_EQ(m.specular, 1.f);
}

// The pattern follows POV-Ray's left-handed space: a point of filmback's world at z is POV-Ray's
// -z, and the pigment's own transforms apply there.
TEST(PovAppearance, PatternsAreEvaluatedInPovRaysSpace) {
  Texture t = plain_texture({0.5, 0.5, 0.5}, 1);
  t.pigment.pattern = Pattern::kGradient;
  t.pigment.gradient = {0, 0, 3};  // normalised, as POV-Ray does
  t.pigment.colour_map = {{0, {0, 0, 0}}, {1, {1, 1, 1}}};
  t.pigment.pattern_from_world = Transform::scale({1, 1, 0.5});  // `scale 2` on z
  const Material m = make_material(t, {}, 1.0, {1, 1, 1});
  ASSERT_TRUE(m.base_color_pattern);
  EXPECT_EQ(m.base_color.x, 1.f);  // diffuse 1 times the pattern
  // world z = 0.5: POV-Ray z = -0.5, pattern z = -0.25, gradient value 0.75.
  EXPECT_NEAR(evaluate_solid(*m.base_color_pattern, {0, 0, 0.5}).rgb.x, 0.75, 1e-4);
}

// The mapping's radiometry with filmback's own BSDF and light sampler: a Lambertian albedo
// rho d lit by intensity pi c gives rho d c cos(theta) at any distance, POV-Ray's diffuse term.
TEST(PovAppearance, DiffuseRadiometryIsPovRaysFormula) {
  Scene pov;
  LightSource l;
  l.location = {1, 4, -2};
  l.colour = {1, 0.8, 0.5};
  pov.lights = {l};
  fb::Scene scene;
  Diagnostics diagnostics;
  convert_lights(pov, scene, diagnostics);
  const Material m = make_material(plain_texture({0.9, 0.6, 0.3}, 0.7), {}, 1.0, {1, 1, 1});
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  BsdfParams params;
  params.base_color = m.base_color, params.specular = m.specular, params.roughness = m.roughness;
  const Bsdf bsdf(params);
  for (Vec3d p : {Vec3d{0, 0, 0}, Vec3d{3, 0, 1}, Vec3d{-5, 0, -8}}) {
    const float u[3] = {0.5f, 0.5f, 0.5f};
    fb_light_sample s;
    ASSERT_TRUE(sampler.sample(Vec3f(p), u, s));
    const Vec3f wi(s.direction);  // the surface is the plane y = 0, normal +y
    const Vec3f local{wi.x, wi.z, wi.y}, wo{0, 0, 1};
    const Rgb radiance = bsdf.eval(wo, local) * Rgb(s.radiance) * (local.z / s.pdf);
    const Vec3d to_light = world_from_pov(l.location) - p;
    const double cos_theta = to_light.y / std::sqrt(dot(to_light, to_light));
    EXPECT_NEAR(radiance.x, 0.9 * 0.7 * 1.0 * cos_theta, 1e-5);
    EXPECT_NEAR(radiance.y, 0.6 * 0.7 * 0.8 * cos_theta, 1e-5);
    EXPECT_NEAR(radiance.z, 0.3 * 0.7 * 0.5 * cos_theta, 1e-5);
  }
}

TEST(PovAppearance, LightsArePlacedInFilmbacksWorldWithPovRaysSemantics) {
  Scene pov;
  LightSource spot;
  spot.kind = LightKind::kSpot;
  spot.location = {0, 5, -5};
  spot.point_at = {0, 0, 0};
  spot.radius_deg = 20, spot.falloff_deg = 30, spot.tightness = 5;
  spot.fade_distance = 3, spot.fade_power = 2;
  spot.shadowless = true;
  LightSource area;
  area.location = {1, 2, 3};
  area.area = true;
  area.axis1 = {2, 0, 0}, area.axis2 = {0, 0, 4};
  area.size1 = 3, area.size2 = 5;
  pov.lights = {spot, area};
  fb::Scene out;
  Diagnostics diagnostics;
  convert_lights(pov, out, diagnostics);
  ASSERT_EQ(out.lights.size(), 2u);
  const Light& s = out.lights[0];
  EXPECT_EQ(s.type, LightType::kSpot);
  EXPECT_EQ(s.spot_falloff, SpotFalloff::kPov);
  EXPECT_EQ(s.decay, LightDecay::kPovRay);
  EXPECT_FALSE(s.casts_shadows);
  EXPECT_NEAR(s.spot_inner_angle_rad, 20 * kPi / 180, 1e-12);
  EXPECT_NEAR(s.spot_outer_angle_rad, 30 * kPi / 180, 1e-12);
  EXPECT_NEAR(s.intensity.x, kPi, 1e-6);
  const Vec3d at = s.world_from_light.point({0, 0, 0});
  EXPECT_NEAR(at.z, 5, 1e-12);  // POV-Ray's z = -5 is filmback's +5
  const Vec3d aim = s.world_from_light.vector({0, 0, -1});
  EXPECT_NEAR(aim.y, -std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(aim.z, -std::sqrt(0.5), 1e-9);
  const Light& a = out.lights[1];
  EXPECT_EQ(a.area_size1, 3u);
  EXPECT_EQ(a.area_size2, 5u);
  const Vec3d axis2 = a.world_from_light.vector(a.area_axis2);
  EXPECT_NEAR(axis2.z, -4, 1e-12);  // mirrored like everything else
}

TEST(PovAppearance, SkySphereIsBakedIntoTheWorldOverTheBackground) {
  Scene pov;
  pov.background = {0, 0, 0.5};
  SkySphere sky;
  Pigment gradient;
  gradient.pattern = Pattern::kGradient;
  gradient.gradient = {0, 1, 0};
  // Opaque white above the horizon, see-through (transmit 1) below it.
  gradient.colour_map = {
      {0, {1, 1, 1, 0, 0}}, {0.5, {1, 1, 1, 0, 0}}, {0.5, {0, 0, 0, 0, 1}}, {1, {0, 0, 0, 0, 1}}};
  sky.pigments = {gradient};
  pov.sky_sphere = sky;
  fb::Scene out;
  Diagnostics diagnostics;
  convert_environment(pov, out, diagnostics);
  EXPECT_FLOAT_EQ(out.background.z, 0.5f);
  ASSERT_TRUE(out.environment);
  EXPECT_EQ(out.environment->width, kSkyWidth);
  const EnvironmentLight env(*out.environment);
  // gradient y: 0.3 up gives 0.3 (white); below the horizon, -0.3 wraps to 0.7 (transparent).
  const Rgb up = env.radiance(normalize(Vec3f{0.9f, 0.3f, 0.2f}));
  const Rgb down = env.radiance(normalize(Vec3f{0.2f, -0.3f, -0.9f}));
  EXPECT_NEAR(up.x, 1, 1e-3);
  EXPECT_NEAR(down.x, 0, 1e-3);
  EXPECT_NEAR(down.z, 0.5, 1e-3);  // the background shows through
}

// Tolerances of NormalPatternsAndLayeredTexturesRenderAsPovRayDoes, three times what it measured
// (docs/pov.md "Normals"): per pixel 0.33 % (marble: the pixels where the triangle wave's kink
// falls inside the derivative's tetrahedron) and 0.002 % (layers); bumps, whose noise is not
// POV-Ray's, +0.7 % in the image mean and -5.5 % in the rms of light and shade about the flat
// plane (about 1600 bump cells in view: a few % of sampling spread in each statistic). A sign or
// scale error in the normal moves these by tens of %.
constexpr double kNormalLayerPixelTolerance = 0.01;
constexpr double kBumpMeanTolerance = 0.03, kBumpSpreadTolerance = 0.15;

// Tolerances of ImageMapsRenderAsPovRayDoes (docs/pov.md "Image maps"): per value, on average and
// at worst, about ten times what it measured (0.018 % and 0.0002 with bilinear interpolation,
// 16-bit rounding otherwise). A texel off by one, a flipped row order or a wrong decoding curve
// differs by tens of %.
constexpr double kImageMapPixelTolerance = 0.002, kImageMapLargestDifference = 0.002;

// filmback's import of `pov_file` for size x size pixels; `warnings`: how many it reported.
fb::Scene import_square(const std::filesystem::path& pov_file, int size, size_t& warnings) {
  Diagnostics diagnostics;
  ImportOptions import;
  import.resolution = {uint32_t(size), uint32_t(size)};
  fb::Scene scene = import_pov(pov_file, import, diagnostics);
  warnings = diagnostics.count();
  return scene;
}

// filmback's render of `scene` at size x size pixels, quietly.
RenderResult render_square(const fb::Scene& scene, int size, uint32_t samples, const char* filter) {
  RenderOptions options;
  options.width = options.height = uint32_t(size);
  options.samples_per_pixel = samples;
  options.filter = filter;
  options.show_progress = false;
  return RenderJob(scene, options, test::loader()).run();
}

struct LightCase {
  const char* name;
  const char* pov;  // the light_source statement
  LightSource light;
};

// A diffuse plane lit by a point light, a fading point light and a spotlight, rendered by POV-Ray
// (linear 16-bit output) and by filmback through this mapping: the mean relative difference over
// the lit pixels stays below 0.5 % (measured: docs/pov.md, "Appearance").
TEST(PovAppearance, DiffusePlaneRendersAsPovRayDoes) {
  if (std::system("command -v povray > /dev/null 2>&1") != 0) GTEST_SKIP() << "no povray";
  LightSource point;
  point.location = {1, 2, -3};
  point.colour = {1, 0.9, 0.8};
  LightSource fading = point;
  fading.fade_distance = 2, fading.fade_power = 2;
  LightSource spot = point;
  spot.kind = LightKind::kSpot;
  spot.location = {0.5, 1, -4};
  spot.point_at = {-0.5, 0, 0};
  spot.radius_deg = 10, spot.falloff_deg = 25, spot.tightness = 4;
  const LightCase cases[] = {
      {"point", "light_source { <1,2,-3> rgb <1,0.9,0.8> }", point},
      {"fading", "light_source { <1,2,-3> rgb <1,0.9,0.8> fade_distance 2 fade_power 2 }", fading},
      {"spot",
       "light_source { <0.5,1,-4> rgb <1,0.9,0.8> spotlight point_at <-0.5,0,0> radius 10 "
       "falloff 25 tightness 4 }",
       spot}};
  constexpr int kSize = 48;
  const std::filesystem::path dir = test::scratch_dir();
  for (const LightCase& c : cases) {
    const std::filesystem::path pov_file = dir / (std::string(c.name) + ".pov");
    std::ofstream(pov_file)
        << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n"
           "camera { orthographic location <0,0,-10> look_at <0,0,0> right x*4 up y*4 }\n"
        << c.pov
        << "\nplane { -z, 0 pigment { rgb <0.8,0.5,0.3> } finish { ambient 0 diffuse 0.7 } }\n";
    std::string why;
    const std::vector<float> reference = test::povray_render(pov_file, kSize, kSize, why);
    ASSERT_FALSE(reference.empty()) << why;

    // The same scene in filmback: a quad on z = 0 facing the camera at +z (POV-Ray's -z).
    test::GltfBuilder gltf;
    test::GltfBuilder::Node quad;
    quad.mesh = gltf.mesh({{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}}, {0, 1, 2, 0, 2, 3},
                          gltf.material({1, 1, 1}), 5125, std::vector<Vec3f>(4, Vec3f{0, 0, 1}));
    gltf.node(quad);
    test::GltfBuilder::Node camera;
    camera.camera = gltf.orthographic_camera(2, 2, 0.1, 100);
    camera.translation = {0, 0, 10};
    gltf.node(camera);
    Diagnostics diagnostics;
    fb::Scene scene = import_gltf(gltf.write(dir / (std::string(c.name) + ".gltf")), diagnostics);
    Texture texture = plain_texture({0.8, 0.5, 0.3}, 0.7);
    texture.finish.ambient = {0, 0, 0};
    scene.materials[0] = make_material(texture, {}, 1.0, {1, 1, 1});
    Scene pov;
    pov.lights = {c.light};
    convert_lights(pov, scene, diagnostics);
    const RenderResult result = render_square(scene, kSize, 16, "box");

    double sum = 0;
    int lit = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const double expected = reference[(size_t(y) * kSize + x) * 3 + ch];
          if (expected < 0.02) continue;  // outside the spot: relative error means nothing
          sum += std::abs(result.image.at(x, y, ch) - expected) / expected;
          ++lit;
        }
    ASSERT_GT(lit, kSize * kSize / 4) << c.name;
    const double mean_relative = sum / lit;
    RecordProperty(std::string(c.name) + "_mean_relative_difference",
                   std::to_string(mean_relative));
    std::printf("%s: mean relative difference to POV-Ray %.4f %% over %d values\n", c.name,
                100 * mean_relative, lit);
    EXPECT_LT(mean_relative, 0.005) << c.name;
  }
}

struct PatternCase {
  const char* pov;  // the pigment's body as POV-Ray reads it
  Pigment pigment;  // the same, as the SDL evaluator leaves it
};

Pigment value_pattern(Pattern kind, Matrix pattern_from_world = Matrix()) {
  Pigment p;
  p.pattern = kind;
  p.colour_map = {{0, {0, 0, 0}}, {1, {1, 1, 1}}};
  p.pattern_from_world = pattern_from_world;
  return p;
}

// Deterministic patterns (no noise) against POV-Ray's render of them on a tilted plane, seen
// through an orthographic camera: pixel (i, j) shows POV-Ray's point (x, y, -y), filmback's
// (x, y, y). List patterns may differ only on cell borders; value patterns agree to 16-bit
// rounding except in the few pixels straddling a jump.
TEST(PovAppearance, DeterministicPatternsMatchPovRaysRenders) {
  if (std::system("command -v povray > /dev/null 2>&1") != 0) GTEST_SKIP() << "no povray";
  const auto scale = [](double x, double y, double z) { return Transform::scale({x, y, z}); };
  const auto translate = [](double x, double y, double z) {
    return Transform::translate({x, y, z});
  };
  std::vector<PatternCase> cases;
  {
    Pigment p;
    p.pattern = Pattern::kChecker;
    Pigment red, blue;
    red.colour = {1, 0, 0}, blue.colour = {0, 0, 1};
    red.pattern_from_world = blue.pattern_from_world = scale(2, 2, 2);
    p.list = {red, blue};
    p.pattern_from_world = scale(2, 2, 2);
    cases.push_back({"checker rgb <1,0,0>, rgb <0,0,1> scale 0.5", p});
  }
  {
    Pigment p;
    p.pattern = Pattern::kHexagon;  // POV-Ray's default blue, green, red
    p.pattern_from_world = scale(1 / 0.3, 1 / 0.3, 1 / 0.3);
    cases.push_back({"hexagon scale 0.3", p});
  }
  {
    Pigment p;
    p.pattern = Pattern::kBrick;
    Pigment mortar, brick;
    mortar.colour = {0.2, 0.2, 0.2}, brick.colour = {0.9, 0.4, 0.3};
    p.list = {mortar, brick};
    p.pattern_from_world = scale(10, 10, 10);
    cases.push_back({"brick rgb 0.2, rgb <0.9,0.4,0.3> scale 0.1", p});
  }
  {
    Pigment p = value_pattern(Pattern::kGradient, scale(1 / 0.7, 2, 1) * translate(-0.2, -0.1, 0));
    p.gradient = {1, 1, 0};
    cases.push_back(
        {"gradient <1,1,0> color_map { [0 rgb 0] [1 rgb 1] } scale <0.7,0.5,1> "
         "translate <0.2,0.1,0>",
         p});
  }
  {
    Pigment p = value_pattern(Pattern::kGradient);
    p.gradient = {0, 1, 0};
    p.wave = Wave::kSine, p.frequency = 2, p.phase = 0.1;
    cases.push_back(
        {"gradient y sine_wave frequency 2 phase 0.1 color_map { [0 rgb 0] [1 rgb 1] }", p});
  }
  cases.push_back({"marble color_map { [0 rgb 0] [1 rgb 1] }", value_pattern(Pattern::kMarble)});
  cases.push_back({"wood color_map { [0 rgb 0] [1 rgb 1] } scale 0.3",
                   value_pattern(Pattern::kWood, scale(1 / 0.3, 1 / 0.3, 1 / 0.3))});
  cases.push_back({"onion color_map { [0 rgb 0] [1 rgb 1] } scale 0.5",
                   value_pattern(Pattern::kOnion, scale(2, 2, 2))});
  cases.push_back({"leopard color_map { [0 rgb 0] [1 rgb 1] } scale 0.1",
                   value_pattern(Pattern::kLeopard, scale(10, 10, 10))});
  {
    Pigment p;  // POV-Ray's default radial colour map
    p.pattern = Pattern::kRadial;
    p.frequency = 3;
    cases.push_back({"radial frequency 3", p});
  }
  {
    Pigment p = value_pattern(Pattern::kSpiral1, scale(2, 2, 2));
    p.spiral_arms = 3;
    cases.push_back({"spiral1 3 color_map { [0 rgb 0] [1 rgb 1] } scale 0.5", p});
  }
  {
    Pigment p = value_pattern(Pattern::kSpiral2, scale(2, 2, 2));
    p.spiral_arms = 2;
    cases.push_back({"spiral2 2 color_map { [0 rgb 0] [1 rgb 1] } scale 0.5", p});
  }

  // Four patterns per render, one in each quadrant of the image (a clipped plane each), to run
  // POV-Ray three times rather than twelve.
  constexpr int kSize = 128, kHalf = kSize / 2;
  const std::filesystem::path dir = test::scratch_dir();
  for (size_t first = 0; first < cases.size(); first += 4) {
    const std::filesystem::path pov_file = dir / ("patterns" + std::to_string(first) + ".pov");
    std::ofstream scene(pov_file);
    scene << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n"
             "camera { orthographic location <0,0,-10> look_at <0,0,0> right x*4 up y*4 }\n";
    for (size_t q = 0; q < 4 && first + q < cases.size(); ++q) {
      const int x0 = q % 2 ? 0 : -2, y0 = q / 2 ? -2 : 0;  // left to right, top to bottom
      scene << "plane { <0,1,1>, 0 pigment { " << cases[first + q].pov
            << " } finish { ambient 0 diffuse 0 emission 1 } clipped_by { box { <" << x0 << ","
            << y0 << ",-10>, <" << x0 + 2 << "," << y0 + 2 << ",10> } } }\n";
    }
    scene.close();
    std::string why;
    const std::vector<float> reference = test::povray_render(pov_file, kSize, kSize, why);
    ASSERT_FALSE(reference.empty()) << why;
    for (size_t q = 0; q < 4 && first + q < cases.size(); ++q) {
      const PatternCase& c = cases[first + q];
      Texture texture = plain_texture({0, 0, 0}, 1);
      texture.pigment = c.pigment;
      const Material m = make_material(texture, {}, 1.0, {1, 1, 1});
      ASSERT_TRUE(m.base_color_pattern) << c.pov;
      int differing = 0;
      double sum = 0;
      const int row = int(q / 2), column = int(q % 2);  // the quadrant
      for (int j = row * kHalf; j < (row + 1) * kHalf; ++j)
        for (int i = column * kHalf; i < (column + 1) * kHalf; ++i) {
          const double x = -2 + (i + 0.5) * 4 / kSize, y = 2 - (j + 0.5) * 4 / kSize;
          const Rgb ours = evaluate_solid(*m.base_color_pattern, {x, y, y}).rgb;
          double worst = 0;
          for (int ch = 0; ch < 3; ++ch) {
            const double d = std::abs(ours[ch] - reference[(size_t(j) * kSize + i) * 3 + ch]);
            worst = std::max(worst, d);
            sum += d;
          }
          if (worst > 0.01) ++differing;
        }
      const double fraction = double(differing) / (kHalf * kHalf);
      std::printf("%-40.40s: %5.2f %% of pixels differ, mean |difference| %.5f\n", c.pov,
                  100 * fraction, sum / (3 * kHalf * kHalf));
      EXPECT_LT(fraction, 0.005) << c.pov;
    }
  }
}

// The whole chain on a .pov file: import_pov (the SDL evaluator, the camera, geometry and
// appearance converters) and a filmback render, against POV-Ray's render of the same file. A
// checkered sphere (an analytic solid with a rotated solid texture) under a point light and a
// fading fill light; one sphere alone, so that no light bounces between surfaces (which POV-Ray
// does not compute). Both trace through each pixel centre (POV-Ray -A; filmback a 0.001 px box
// filter). Each filmback sample picks one of the two lights, which leaves about 1.5 % noise per
// pixel at 1024 samples, so the pixels are compared in 4 x 4 blocks inside the sphere (noise
// about 0.4 %) and the mean signed difference (a bias) over all lit pixels.
TEST(PovAppearance, SdlSceneRendersAsPovRayDoes) {
  if (std::system("command -v povray > /dev/null 2>&1") != 0) GTEST_SKIP() << "no povray";
  constexpr int kWidth = 96, kHeight = 72;
  const std::filesystem::path dir = test::scratch_dir();
  const std::filesystem::path pov_file = dir / "sphere.pov";
  std::ofstream(pov_file) << R"(#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0.3, 0.8, -4> look_at <0, 0, 0> angle 40 }
light_source { <3, 4, -5> rgb <1, 0.95, 0.9> }
light_source { <-4, 1, -2> rgb 0.4 fade_distance 3 fade_power 1 }
sphere { <0, 0, 0>, 1
  pigment { checker rgb <0.9, 0.3, 0.2>, rgb <0.2, 0.5, 0.9> scale 0.5 rotate <0, 20, 0> }
  finish { ambient 0 diffuse 0.8 }
}
)";
  std::string why;
  const std::vector<float> reference = test::povray_render(pov_file, kWidth, kHeight, why);
  ASSERT_FALSE(reference.empty()) << why;

  Diagnostics diagnostics;
  ImportOptions import;
  import.resolution = {uint32_t(kWidth), uint32_t(kHeight)};
  const fb::Scene scene = import_pov(pov_file, import, diagnostics);
  ASSERT_EQ(scene.materials.size(), 1u);
  ASSERT_TRUE(scene.materials[0].base_color_pattern);
  RenderOptions options;
  options.width = uint32_t(kWidth), options.height = uint32_t(kHeight);
  options.samples_per_pixel = 1024;
  options.filter = "box:radius=0.001";
  options.show_progress = false;
  const RenderResult result = RenderJob(scene, options, test::loader()).run();

  auto lit = [&](int x, int y) { return reference[(size_t(y) * kWidth + x) * 3] > 0.02; };
  double signed_sum = 0;
  int lit_values = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int ch = 0; ch < 3 && lit(x, y); ++ch) {
        const double expected = reference[(size_t(y) * kWidth + x) * 3 + ch];
        signed_sum += (result.image.at(x, y, ch) - expected) / expected;
        ++lit_values;
      }
  ASSERT_GT(lit_values, kWidth * kHeight / 2);
  constexpr int kBlock = 4;
  int blocks = 0;
  double worst_block = 0;
  for (int by = 0; by + kBlock <= kHeight; by += kBlock)
    for (int bx = 0; bx + kBlock <= kWidth; bx += kBlock) {
      bool inside = true;
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x)
          inside = inside && lit(x, y);
      if (!inside) continue;
      ++blocks;
      for (int ch = 0; ch < 3; ++ch) {
        double ours = 0, expected = 0;
        for (int y = by; y < by + kBlock; ++y)
          for (int x = bx; x < bx + kBlock; ++x) {
            ours += result.image.at(x, y, ch);
            expected += reference[(size_t(y) * kWidth + x) * 3 + ch];
          }
        worst_block = std::max(worst_block, std::abs(ours - expected) / expected);
      }
    }
  ASSERT_GT(blocks, 100);
  const double bias = signed_sum / lit_values;
  std::printf(
      "checkered sphere: mean signed difference to POV-Ray %+.3f %%, worst of %d 4x4 blocks "
      "%.2f %%\n",
      100 * bias, blocks, 100 * worst_block);
  EXPECT_LT(std::abs(bias), 0.002);
  // A block straddling a checker border has the border where POV-Ray's pixel centres put it.
  EXPECT_LT(worst_block, 0.03);
}

// Normal patterns and layered textures through the whole chain (import_pov and a render)
// against POV-Ray, on a plane facing an orthographic camera under one point light, so that every
// pixel is direct light alone. Deterministic normals (marble, whose slope filmback
// differentiates numerically as POV-Ray does) and layers (a gradient of filter and transmit over
// a plain base) are compared pixel by pixel: mean relative difference over the lit values. Bumps
// come from a noise that differs from POV-Ray's point by point (solid_pattern.h), so their image
// is compared by its statistics: the mean, and the spread the bumps put into the shading (the
// standard deviation of the image minus POV-Ray's render of the flat plane).
// Measured: docs/pov.md "Normals" and "Layered textures".
TEST(PovAppearance, NormalPatternsAndLayeredTexturesRenderAsPovRayDoes) {
  if (std::system("command -v povray > /dev/null 2>&1") != 0) GTEST_SKIP() << "no povray";
  struct Case {
    const char* name;
    const char* appearance;  // inside the plane
    bool per_pixel;
  };
  const auto write_scene = [](const std::filesystem::path& file, const char* appearance) {
    std::ofstream(file) << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n"
                           "camera { orthographic location <0,0,-10> look_at <0,0,0> "
                           "right x*4 up y*4 }\n"
                           "light_source { <1, 2, -3> rgb 1 }\n"
                           "plane { -z, 0 "
                        << appearance << " }\n";
  };
  const Case cases[] = {
      {"marble",
       "pigment { rgb <0.8, 0.7, 0.6> } finish { ambient 0 diffuse 0.8 } "
       "normal { marble 0.8 scale 0.5 }",
       true},
      {"layered",
       "texture { pigment { rgb <0.8, 0.6, 0.3> } finish { ambient 0 diffuse 0.8 } }\n"
       "texture { pigment { gradient x color_map { [0 rgbf <0.2, 0.3, 0.9, 0.9>] "
       "[1 rgbt <0.9, 0.2, 0.1, 0.3>] } scale 0.7 } finish { ambient 0 diffuse 0.6 } }",
       true},
      {"bumps",
       "pigment { rgb <0.8, 0.7, 0.6> } finish { ambient 0 diffuse 0.8 } "
       "normal { bumps 0.5 scale 0.1 }",
       false},
  };
  constexpr int kSize = 64;
  const std::filesystem::path dir = test::scratch_dir();
  std::string why;
  write_scene(dir / "flat.pov", "pigment { rgb <0.8, 0.7, 0.6> } finish { ambient 0 diffuse 0.8 }");
  const std::vector<float> flat = test::povray_render(dir / "flat.pov", kSize, kSize, why);
  ASSERT_FALSE(flat.empty()) << why;
  for (const Case& c : cases) {
    const std::filesystem::path pov_file = dir / (std::string(c.name) + ".pov");
    write_scene(pov_file, c.appearance);
    const std::vector<float> reference = test::povray_render(pov_file, kSize, kSize, why);
    ASSERT_FALSE(reference.empty()) << why;
    size_t warnings = 0;
    const fb::Scene scene = import_square(pov_file, kSize, warnings);
    EXPECT_EQ(warnings, 0u) << c.name;
    const RenderResult result = render_square(scene, kSize, 4, "box:radius=0.001");

    double relative_sum = 0, ours_sum = 0, pov_sum = 0, ours_sq = 0, pov_sq = 0;
    int values = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const double expected = reference[(size_t(y) * kSize + x) * 3 + ch];
          const double ours = result.image.at(x, y, ch);
          const double flat_value = flat[(size_t(y) * kSize + x) * 3 + ch];
          ours_sum += ours, pov_sum += expected;
          ours_sq += (ours - flat_value) * (ours - flat_value);
          pov_sq += (expected - flat_value) * (expected - flat_value);
          if (expected < 0.02) continue;
          relative_sum += std::abs(ours - expected) / expected;
          ++values;
        }
    const int n = kSize * kSize * 3;
    const double ours_mean = ours_sum / n, pov_mean = pov_sum / n;
    // the root mean square of the bumps' light and shade about the flat plane's
    const double ours_spread = std::sqrt(ours_sq / n), pov_spread = std::sqrt(pov_sq / n);
    const double mean_relative = values ? relative_sum / values : 1;
    std::printf(
        "%s: mean relative difference %.3f %% over %d values; image mean %.4f (POV-Ray %.4f), "
        "rms about the flat plane %.4f (POV-Ray %.4f)\n",
        c.name, 100 * mean_relative, values, ours_mean, pov_mean, ours_spread, pov_spread);
    RecordProperty(std::string(c.name) + "_mean_relative_difference",
                   std::to_string(mean_relative));
    if (c.per_pixel) {
      ASSERT_GT(values, n / 2) << c.name;
      EXPECT_LT(mean_relative, kNormalLayerPixelTolerance) << c.name;
    } else {
      EXPECT_LT(std::abs(ours_mean / pov_mean - 1), kBumpMeanTolerance) << c.name;
      EXPECT_LT(std::abs(ours_spread / pov_spread - 1), kBumpSpreadTolerance) << c.name;
    }
  }
}

// An 8 x 4 RGB image of distinct 8-bit colours (x, y, and their mix in the three channels).
void write_image_map_test_image(const std::filesystem::path& file) {
  constexpr int kWidth = 8, kHeight = 4;
  std::vector<unsigned char> pixels;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      pixels.insert(pixels.end(), {(unsigned char)(30 * x + 15), (unsigned char)(60 * y + 20),
                                   (unsigned char)((37 * (x + 3 * y)) % 256)});
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(kWidth, kHeight, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
}

// image_map through the whole chain (import_pov and a render) against POV-Ray, pixel by pixel:
// a plane under one point light, an orthographic camera seeing the image's unit square and half
// a unit around it, each texel 4 x 8 pixels (no pixel centre on a texel's edge).
// The 8-bit PNG decoded by the sRGB curve, repeated, read once (clear around it: black), and
// read linear (`gamma 1.0`) with bilinear interpolation; scaled and rotated.
TEST(PovAppearance, ImageMapsRenderAsPovRayDoes) {
  if (std::system("command -v povray > /dev/null 2>&1") != 0) GTEST_SKIP() << "no povray";
  struct Case {
    const char* name;
    const char* pigment;
  };
  const Case cases[] = {
      {"repeated", "image_map { png \"map.png\" }"},
      {"once", "image_map { png \"map.png\" once }"},
      {"linear_bilinear", "image_map { png \"map\" gamma 1.0 interpolate 2 }"},
      {"transformed", "image_map { \"map.png\" } scale <0.7, 0.4, 1> rotate 20*z"},
  };
  constexpr int kSize = 64;
  const std::filesystem::path dir = test::scratch_dir();
  write_image_map_test_image(dir / "map.png");
  for (const Case& c : cases) {
    const std::filesystem::path pov_file = dir / (std::string(c.name) + ".pov");
    std::ofstream(pov_file) << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n"
                               "camera { orthographic location <0.5,0.5,-10> look_at <0.5,0.5,0> "
                               "right x*2 up y*2 }\n"
                               "light_source { <0.3, 0.8, -3> rgb 1 }\n"
                               "plane { -z, 0 pigment { "
                            << c.pigment << " } finish { ambient 0 diffuse 0.8 } }\n";
    std::string why;
    const std::vector<float> reference = test::povray_render(pov_file, kSize, kSize, why);
    ASSERT_FALSE(reference.empty()) << why;
    size_t warnings = 0;
    const fb::Scene scene = import_square(pov_file, kSize, warnings);
    EXPECT_EQ(warnings, 0u) << c.name;
    const RenderResult result = render_square(scene, kSize, 1, "box:radius=0.001");
    double relative_sum = 0, largest = 0;
    int values = 0, dark = 0, dark_here = 0;  // dark: off a `once` image, or a black texel
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const double expected = reference[(size_t(y) * kSize + x) * 3 + ch];
          const double ours = result.image.at(x, y, ch);
          largest = std::max(largest, std::abs(ours - expected));
          if (expected < 0.01) {
            ++dark, dark_here += ours < 0.01;
            continue;
          }
          relative_sum += std::abs(ours - expected) / expected;
          ++values;
        }
    const double mean_relative = values ? relative_sum / values : 1;
    std::printf("%s: mean relative difference %.4f %% over %d values, largest %.5f\n", c.name,
                100 * mean_relative, values, largest);
    RecordProperty(std::string(c.name) + "_mean_relative_difference",
                   std::to_string(mean_relative));
    ASSERT_GT(values, kSize * kSize / 2) << c.name;
    EXPECT_EQ(dark_here, dark) << c.name;
    EXPECT_LT(mean_relative, kImageMapPixelTolerance) << c.name;
    EXPECT_LT(largest, kImageMapLargestDifference) << c.name;
  }
}

}  // namespace
}  // namespace fb::pov
