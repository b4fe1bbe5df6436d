// Surface::closure_weight, what the DiffCol and GlossCol passes hold, against Cycles 3.4's passes
// of the same materials seen square-on (tests/blender/gloss_shot.py rendered by Blender 3.4.1's
// Cycles, each patch's mean; docs/blender.md "Passes"), and glTF's model against its lobes.
#include <gtest/gtest.h>

#include "core/shading/fresnel.h"
#include "core/shading/surface.h"

namespace fb {
namespace {

constexpr Rgb kGlossShotColour{0.8f, 0.3f, 0.1f};  // gloss_shot.py's COLOUR
constexpr Rgb kClosureWeightWhite{1.f, 1.f, 1.f};

// A surface seen square-on from its front, as gloss_shot.py's orthographic camera sees its patches.
Surface square_on_surface() {
  Surface s;
  s.begin({{0.f, 0.f, 1.f}, {0.f, 0.f, 1.f}, {0.f, 0.f, 1.f}, false});
  return s;
}

void expect_closure_weight(const Surface& s, ClosureKind kind, Rgb expected, const char* what,
                           float tolerance = 1e-5f) {
  const Rgb w = s.closure_weight(kind);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(w[c], expected[c], tolerance) << what << " channel " << c;
}

PrincipledInputs gloss_shot_principled(float metallic, float transmission, float roughness) {
  PrincipledInputs in;
  in.base_color = kGlossShotColour;
  in.metallic = metallic;
  in.transmission = transmission;
  in.roughness = roughness;
  return in;
}

TEST(ClosureWeight, PrincipledAsCyclesPasses) {
  struct Case {
    const char* name;
    PrincipledInputs in;
    Rgb diffuse, glossy;  // Cycles' DiffCol and GlossCol
  };
  PrincipledInputs specular1 = gloss_shot_principled(0.f, 0.f, 0.4f);
  specular1.specular = 1.f;
  PrincipledInputs multi_glass = gloss_shot_principled(0.f, 1.f, 0.5f);
  multi_glass.distribution = Distribution::kMultiGgx;
  PrincipledInputs clearcoat = gloss_shot_principled(0.f, 0.f, 0.4f);
  clearcoat.clearcoat = 1.f;
  // Cycles' glass reflection at normal incidence: the Fresnel of Blender's default ior 1.45.
  const float f0 = fresnel_dielectric_cos(1.f, 1.45f);
  const Case cases[] = {
      {"Dielectric", gloss_shot_principled(0.f, 0.f, 0.4f), kGlossShotColour, kClosureWeightWhite},
      {"Specular1", specular1, kGlossShotColour, kClosureWeightWhite},
      {"Metal", gloss_shot_principled(1.f, 0.f, 0.3f), {}, kClosureWeightWhite},
      {"HalfMetal", gloss_shot_principled(0.5f, 0.f, 0.3f), kGlossShotColour * 0.5f,
       kClosureWeightWhite},
      {"Glass", gloss_shot_principled(0.f, 1.f, 0.f), {}, kClosureWeightWhite * f0},
      {"RoughGlass", gloss_shot_principled(0.f, 1.f, 0.5f), {}, kClosureWeightWhite * f0},
      {"HalfGlass", gloss_shot_principled(0.f, 0.5f, 0.2f), kGlossShotColour * 0.5f,
       kClosureWeightWhite * (0.5f + 0.5f * f0)},
      {"MultiGlass", multi_glass, {}, {}},
      {"Clearcoat", clearcoat, kGlossShotColour, kClosureWeightWhite * 2.f},
  };
  EXPECT_NEAR(f0, 0.0337f, 5e-5f);  // Cycles' GlossCol of the Glass patch
  for (const Case& c : cases) {
    Surface s = square_on_surface();
    s.add_principled(c.in, kClosureWeightWhite);
    expect_closure_weight(s, ClosureKind::kDiffuse, c.diffuse, c.name);
    expect_closure_weight(s, ClosureKind::kGlossy, c.glossy, c.name);
  }
}

TEST(ClosureWeight, SheenIsDiffuseAndTheGlassRefractionTransmission) {
  // Cycles' DiffCol of the Sheen patch: the base colour plus the sheen closure, white half-tinted
  // towards the base colour's hue (2.3207, 1.1827, 0.7276 measured). The hue is the colour over
  // its luminance, whose weights Cycles takes from its OCIO config (rgb_to_y) and filmback from
  // Rec. 709 rounded: 1.1e-4 apart here.
  PrincipledInputs sheen = gloss_shot_principled(0.f, 0.f, 0.4f);
  sheen.sheen = 1.f;
  Surface s = square_on_surface();
  s.add_principled(sheen, kClosureWeightWhite);
  expect_closure_weight(s, ClosureKind::kDiffuse, {2.3207f, 1.1827f, 0.7276f}, "Sheen", 2e-4f);
  Surface glass = square_on_surface();
  glass.add_principled(gloss_shot_principled(0.f, 1.f, 0.f), kClosureWeightWhite);
  expect_closure_weight(glass, ClosureKind::kTransmission,
                        kGlossShotColour * (1.f - fresnel_dielectric_cos(1.f, 1.45f)), "Glass");
}

TEST(ClosureWeight, GlossyAndMixedNodes) {
  // A Glossy BSDF of colour (0.3, 0.6, 0.9), and the same mixed 0.3 with a Diffuse BSDF: the Mix
  // Shader's factor scales each closure's weight.
  const Rgb glossy_colour{0.3f, 0.6f, 0.9f};
  Surface glossy = square_on_surface();
  glossy.add_glossy(Distribution::kGgx, glossy_colour, 0.3f, {}, kClosureWeightWhite);
  expect_closure_weight(glossy, ClosureKind::kGlossy, glossy_colour, "Glossy");
  expect_closure_weight(glossy, ClosureKind::kDiffuse, {}, "Glossy");
  Surface mix = square_on_surface();
  mix.add_diffuse(kGlossShotColour, 0.f, {}, kClosureWeightWhite * 0.7f);
  mix.add_glossy(Distribution::kGgx, glossy_colour, 0.3f, {}, kClosureWeightWhite * 0.3f);
  expect_closure_weight(mix, ClosureKind::kDiffuse, {0.56f, 0.21f, 0.07f}, "Mix");
  expect_closure_weight(mix, ClosureKind::kGlossy, {0.09f, 0.18f, 0.27f}, "Mix");
}

TEST(ClosureWeight, GltfModelReportsItsLobes) {
  // One specular layer over the whole surface (white: its Fresnel is in its evaluation), the
  // diffuse base and the transmission under it sharing the dielectric part.
  GltfSurfaceParams p;
  p.base_color = kGlossShotColour;
  p.metallic = 0.25f;
  p.transmission = 0.4f;
  p.normal = {0.f, 0.f, 1.f};
  Surface s = square_on_surface();
  s.add_gltf(p);
  expect_closure_weight(s, ClosureKind::kDiffuse, kGlossShotColour * (0.75f * 0.6f), "glTF");
  expect_closure_weight(s, ClosureKind::kGlossy, kClosureWeightWhite, "glTF");
  expect_closure_weight(s, ClosureKind::kTransmission, kGlossShotColour * (0.75f * 0.4f), "glTF");
  // KHR_materials_specular 0: the dielectric does not reflect; the metal still does.
  p.specular = 0.f;
  Surface lambertian = square_on_surface();
  lambertian.add_gltf(p);
  expect_closure_weight(lambertian, ClosureKind::kGlossy, kClosureWeightWhite * 0.25f,
                        "glTF specular 0");
}

}  // namespace
}  // namespace fb
