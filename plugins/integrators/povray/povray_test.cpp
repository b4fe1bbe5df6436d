// The `povray` integrator against POV-Ray 3.7's own renders: small scenes, each showing one
// term of POV-Ray's lighting, rendered by `povray` (one ray through each pixel centre, linear
// 16-bit output) and by filmback with `--integrator povray` through the same pixel centres (a
// 0.001 px box filter), compared by the mean relative difference over the lit values
// (docs/pov.md, "The povray integrator"). The formulas of pov_lighting.h are checked by hand too.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/render/render_job.h"
#include "importers/pov/pov_importer.h"
#include "pov_lighting.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"
#include "support/povray_render.h"

namespace fb {
namespace {

namespace lighting = pov_lighting;

TEST(PovLighting, TermsAreTheFormulasOfPovRay) {
  fb_pov_finish f = lighting::diffuse_finish(0.6f);
  f.brilliance = 3.f;
  const Rgb pigment{0.5f, 0.25f, 1.f}, light{2.f, 2.f, 2.f};
  // diffuse * cos^brilliance * opacity * pigment * light
  const Rgb d = lighting::diffuse(f, 0.5f, 0.8f, pigment, light);
  EXPECT_NEAR(d.x, 0.6 * 0.125 * 0.8 * 0.5 * 2, 1e-6);
  EXPECT_EQ(max_component(lighting::diffuse(f, -0.1f, 1.f, pigment, light)), 0.f);

  // phong: the view mirrored on the normal, against the light, to the phong_size
  f.phong = 0.7f, f.phong_size = 10.f;
  const Vec3f normal{0, 1, 0}, view = normalize(Vec3f{1, -1, 0});
  const Vec3f to_light = normalize(Vec3f{1, 2, 0});
  const double cos_mirror = dot(normalize(Vec3f{1, 1, 0}), to_light);
  EXPECT_NEAR(lighting::phong(f, view, normal, to_light, pigment, light).x,
              0.7 * std::pow(cos_mirror, 10) * 2, 1e-5);
  // specular: Blinn's half vector, exponent 1 / roughness
  f.specular = 0.4f, f.roughness = 0.1f;
  const double cos_half = dot(normalize(to_light - view), normal);
  EXPECT_NEAR(lighting::specular(f, view, normal, to_light, pigment, light).y,
              0.4 * std::pow(cos_half, 10) * 2, 1e-5);

  // reflection from min (facing) to max (grazing) by (1 - cos)^falloff
  f.reflection_min[0] = f.reflection_min[1] = f.reflection_min[2] = 0.1f;
  f.reflection_max[0] = f.reflection_max[1] = f.reflection_max[2] = 0.9f;
  f.reflection_falloff = 2.f;
  EXPECT_NEAR(lighting::reflectivity(f, 0.6f, 1.f, pigment).x, 0.1 + 0.8 * 0.16, 1e-6);
  EXPECT_NEAR(lighting::reflectivity(f, 1.f, 1.f, pigment).x, 0.1, 1e-6);
  // Fresnel's law: ((n - 1) / (n + 1))^2 facing, 1 at grazing
  f.reflection_fresnel = 1;
  f.reflection_min[0] = 0.f, f.reflection_max[0] = 1.f;
  EXPECT_NEAR(lighting::fresnel(1.f, 1.5f), 0.04, 1e-6);
  EXPECT_NEAR(lighting::reflectivity(f, 1e-6f, 1.5f, pigment).x, 1.0, 1e-4);

  // Snell's law through the refracted direction, and total internal reflection past the
  // critical angle
  const Vec3f in = normalize(Vec3f{0.6f, -0.8f, 0});
  const auto out = lighting::refracted(in, normal, 1.5f);
  ASSERT_TRUE(out);
  EXPECT_NEAR(out->x * 1.5, in.x, 1e-6);
  EXPECT_LT(out->y, 0.f);
  EXPECT_TRUE(lighting::refracted(in, normal, 1.f / 1.5f));  // sin 0.6 * 1.5 < 1
  const Vec3f grazing = normalize(Vec3f{0.8f, -0.6f, 0});    // sin 0.8 * 1.5 > 1
  EXPECT_FALSE(lighting::refracted(grazing, normal, 1.f / 1.5f));
}

// A scene's render by POV-Ray and by filmback's `povray` integrator, and how far apart they are.
struct PovComparison {
  double mean_relative = 0;  // over the values POV-Ray renders above 0.02 and below 0.98
  int lit_values = 0;
};

constexpr int kPovCaseSize = 64;

PovComparison compare_with_povray(const std::string& name, const std::string& sdl, uint32_t samples,
                                  const std::string& global_settings) {
  const std::filesystem::path pov_file = test::scratch_dir() / (name + ".pov");
  std::ofstream(pov_file) << "#version 3.7;\nglobal_settings { " << global_settings << " }\n"
                          << sdl;
  std::string why;
  const std::vector<float> reference =
      test::povray_render(pov_file, kPovCaseSize, kPovCaseSize, why);
  EXPECT_FALSE(reference.empty()) << why;
  if (reference.empty()) return {};

  Diagnostics diagnostics;
  ImportOptions import;
  import.resolution = {uint32_t(kPovCaseSize), uint32_t(kPovCaseSize)};
  const Scene scene = import_pov(pov_file, import, diagnostics);
  RenderOptions options;
  options.width = options.height = uint32_t(kPovCaseSize);
  options.samples_per_pixel = samples;
  options.filter = "box:radius=0.001";
  options.integrator = "povray";
  options.show_progress = false;
  const RenderResult result = RenderJob(scene, options, test::loader()).run();

  PovComparison c;
  double sum = 0;
  for (int y = 0; y < kPovCaseSize; ++y)
    for (int x = 0; x < kPovCaseSize; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        const double expected = reference[(size_t(y) * kPovCaseSize + x) * 3 + ch];
        if (!(expected > 0.02 && expected < 0.98)) continue;  // dark, or clipped by the PNG
        sum += std::abs(result.image.at(x, y, ch) - expected) / expected;
        ++c.lit_values;
      }
  c.mean_relative = c.lit_values ? sum / c.lit_values : 0;
  std::printf("%-10s mean relative difference to POV-Ray %.3f %% over %d values\n", name.c_str(),
              100 * c.mean_relative, c.lit_values);
  return c;
}

struct PovCase {
  const char* name;
  const char* sdl;  // after the #version and global_settings lines
  uint32_t samples;
  double
      tolerance;  // on the mean relative difference: three times what was measured, at least 0.5 %
  const char* global_settings = "assumed_gamma 1.0";
};

constexpr const char* kPovCaseCamera =
    "camera { location <0, 1.5, -4> look_at <0, 0.3, 0> angle 45 }\n"
    "background { rgb <0.2, 0.3, 0.5> }\n";

const PovCase kPovCases[] = {
    {"brilliance",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "plane { y, 0 pigment { rgb <0.8, 0.6, 0.3> } finish { ambient 0.1 diffuse 0.7 brilliance 3 "
     "} }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { rgb <0.3, 0.5, 0.9> } finish { ambient 0.2 brilliance "
     "0.5 } }\n",
     1, 0.001},
    {"phong",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { rgb <0.8, 0.2, 0.2> } finish { phong 0.9 phong_size 30 "
     "} }\n",
     1, 0.001},
    {"specular",
     "light_source { <-3, 5, -4> rgb <1, 0.9, 0.8> }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { rgb <0.2, 0.7, 0.3> } finish { specular 0.8 roughness "
     "0.02 metallic 0.5 } }\n",
     1, 0.001},
    {"shadow",
     "light_source { <2, 6, -3> rgb 1 }\n"
     "plane { y, 0 pigment { rgb 0.8 } finish { ambient 0.2 } }\n"
     "box { <-0.5, 0.3, -0.5>, <0.5, 1.3, 0.5> pigment { rgb <0.9, 0.4, 0.1> } }\n"
     "sphere { <1.2, 0.4, -0.8>, 0.4 pigment { rgbf <0.3, 0.9, 0.3, 0.7> } }\n",
     1, 0.001},
    {"mirror",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "plane { y, 0 pigment { checker rgb 0.9, rgb <0.7, 0.1, 0.1> } }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { rgb 0.1 } finish { ambient 0 diffuse 0.2 reflection { "
     "0.1, 0.9 falloff 2 } } }\n",
     1, 0.01},
    {"glass",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "plane { y, 0 pigment { checker rgb 0.9, rgb <0.1, 0.2, 0.7> } }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { rgbf <0.95, 1, 0.95, 0.9> } finish { ambient 0 diffuse "
     "0.1 phong 0.5 reflection { 0.05, 1 fresnel } } interior { ior 1.5 } }\n",
     1, 0.02},
    // A finish without diffuse glows in its pigment's colour at each hit, a pattern's too (a disc,
    // not a plane: a plane's checkers alias at the horizon, where one ray per pixel lands apart).
    {"self_lit_patterns",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "disc { 0, y, 2.5 pigment { checker rgb 0.9, rgb <0.7, 0.1, 0.1> } finish { ambient 1 diffuse "
     "0 "
     "} }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { gradient x color_map { [0 rgb <0.1, 0.2, 0.9>] [1 rgb "
     "<0.9, 0.8, 0.1>] } scale 1.6 translate -0.8 * x } finish { ambient 0.3 emission 0.5 diffuse "
     "0 } }\n",
     1, 0.001},
    {"area_light",
     "light_source { <0, 4, -1> rgb 1 area_light <2, 0, 0>, <0, 0, 2>, 5, 5 }\n"
     "plane { y, 0 pigment { rgb 0.8 } finish { ambient 0.1 } }\n"
     "sphere { <0, 0.8, 0>, 0.6 pigment { rgb <0.9, 0.5, 0.2> } }\n",
     100, 0.02},
    // POV-Ray's fog (docs/pov.md "Fog"): the blend by exp(-depth / distance) with the fog's filter
    // and transmit, complete where rays escape; ground fog thinning above its offset.
    {"fog_constant",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "plane { y, 0 pigment { checker rgb 0.9, rgb <0.1, 0.2, 0.7> } }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { rgb <0.9, 0.5, 0.2> } finish { reflection 0.3 } }\n"
     "fog { distance 5 rgbf <0.6, 0.7, 0.8, 0.4> }\n",
     1, 0.001},
    {"fog_ground",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "plane { y, 0 pigment { checker rgb 0.9, rgb <0.1, 0.2, 0.7> } }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { rgb <0.9, 0.5, 0.2> } }\n"
     "fog { fog_type 2 distance 2 rgbt <0.8, 0.8, 0.7, 0.2> fog_offset 0.3 fog_alt 0.4 }\n",
     1, 0.001},
    // Interior media (docs/pov.md "Media"): a sphere's glowing, absorbing medium over a checker
    // (closed form), and a scattering one lit by the light (sampled along each ray inside), with
    // an opaque box inside that shadows part of it.
    {"media_glow",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "plane { y, 0 pigment { checker rgb 0.9, rgb <0.1, 0.2, 0.7> } }\n"
     "sphere { <0, 0.8, 0>, 0.8 hollow pigment { rgbt 1 } interior { media { emission rgb <0.8, "
     "0.5, 0.2> absorption rgb <0.3, 1, 2> } } }\n",
     1, 0.02},
    {"media_scattering",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "plane { y, 0 pigment { checker rgb 0.9, rgb <0.1, 0.2, 0.7> } }\n"
     "sphere { <0, 0.8, 0>, 0.8 hollow pigment { rgbt 1 } interior { media { scattering { 1, rgb "
     "<0.3, 0.5, 0.8> } absorption 0.2 } } }\n",
     1, 0.05},
    {"media_shadowed",
     "light_source { <3, 5, -4> rgb 1 }\n"
     "plane { y, 0 pigment { checker rgb 0.9, rgb <0.1, 0.2, 0.7> } }\n"
     "sphere { <0, 0.8, 0>, 0.8 hollow pigment { rgbt 1 } interior { media { scattering { 1, rgb "
     "<0.6, 0.8, 1> } } } }\n"
     "box { <0.05, 0.75, -0.3>, <0.35, 1.05, 0> pigment { rgb <0.9, 0.4, 0.1> } }\n",
     16, 0.05},
    // assumed_gamma 2.2: POV-Ray lights in the colours as written and decodes the pixel (File_Gamma
    // 1). Lit in decoded colours (main at 7138630) this scene measured 61 % off (median 39 %),
    // and sample scenes such as textures/patterns/spotted.pov far too bright (issue 19). A disc:
    // a plane's checkers alias at the horizon.
    {"assumed_gamma",
     "light_source { <3, 5, -4> rgb <1, 0.9, 0.7> }\n"
     "disc { 0, y, 2.5 pigment { checker rgb 0.9, rgb <0.1, 0.2, 0.7> } finish { ambient 0.3 } }\n"
     "sphere { <0, 0.8, 0>, 0.8 pigment { rgb <0.9, 0.5, 0.2> } finish { phong 0.6 reflection 0.2 "
     "} }\n",
     1, 0.001, "assumed_gamma 2.2 ambient_light rgb <0.8, 0.9, 1>"},
};

class PovRayIntegrator : public ::testing::TestWithParam<PovCase> {};

TEST_P(PovRayIntegrator, RendersAsPovRayDoes) {
  if (!test::have_povray()) GTEST_SKIP() << "no povray";
  const PovCase& c = GetParam();
  const PovComparison result = compare_with_povray(c.name, std::string(kPovCaseCamera) + c.sdl,
                                                   c.samples, c.global_settings);
  EXPECT_GT(result.lit_values, kPovCaseSize * kPovCaseSize);  // most of the image is lit
  EXPECT_LT(result.mean_relative, c.tolerance);
}

INSTANTIATE_TEST_SUITE_P(Terms, PovRayIntegrator, ::testing::ValuesIn(kPovCases),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace fb
