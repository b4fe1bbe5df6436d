// The node entry points of Surface (node_closures.cpp) against Cycles 3.4's svm_closure.h, and
// the closures' formulas against values computed here from the published equations: Burley
// 2015's retro-reflection, Burley 2012's sheen, the exact dielectric Fresnel behind
// interpolate_fresnel_color.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/math/constants.h"
#include "core/shading/closure.h"
#include "core/shading/fresnel.h"
#include "core/shading/surface.h"

namespace fb {
namespace {

Vec3f direction(double cos_theta, double phi) {
  const double s = std::sqrt(1 - cos_theta * cos_theta);
  return Vec3f(Vec3d{s * std::cos(phi), s * std::sin(phi), cos_theta});
}

Surface surface(Vec3f I) {
  Surface s;
  s.begin({I, {0.f, 0.f, 1.f}, {0.f, 0.f, 1.f}, false});
  return s;
}

const Closure* find(const Surface& s, ClosureType type) {
  for (int i = 0; i < s.closure_count(); ++i)
    if (s.closure(i).type == type) return &s.closure(i);
  return nullptr;
}

// Unpolarised Fresnel reflectance from Snell's law (Born and Wolf), in double.
double fresnel_exact(double cos_i, double eta) {
  const double sin_t2 = (1 - cos_i * cos_i) / (eta * eta);
  if (sin_t2 >= 1) return 1;
  const double cos_t = std::sqrt(1 - sin_t2);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

TEST(NodeClosures, PrincipledDiffuseIsBurleysRetroReflection) {
  const Vec3f I = direction(0.3, 0.0), L = direction(0.7, 2.0);
  PrincipledInputs in;
  in.base_color = {0.5f, 0.25f, 0.125f};
  in.roughness = 0.6f;
  in.metallic = 0.2f;
  in.specular = 0.f;
  Surface s = surface(I);
  s.add_principled(in, {1.f, 1.f, 1.f});
  const Closure* c = find(s, ClosureType::kPrincipledDiffuse);
  ASSERT_NE(c, nullptr);
  EXPECT_NEAR(c->weight.y, 0.25 * 0.8, 1e-6);  // base (1 - metallic)(1 - transmission)
  float pdf;
  const Rgb f = closure_eval(*c, {I, {0, 0, 1}, {0, 0, 1}}, L, pdf);
  // Burley 2015, section 2.3: f = (1/pi) [(1 - FL/2)(1 - FV/2) + RR (FL + FV + FL FV (RR - 1))]
  // with FL, FV Schlick weights and RR = 2 roughness cos^2(theta_d), theta_d the angle of L to H.
  const Vec3d h = Vec3d(normalize(L + I));
  const double cos_d = dot(h, Vec3d(L));
  const double FL = std::pow(1 - 0.7, 5), FV = std::pow(1 - 0.3, 5);
  const double RR = 2 * 0.6 * cos_d * cos_d;
  const double expected =
      0.7 / kPi * ((1 - FL / 2) * (1 - FV / 2) + RR * (FL + FV + FL * FV * (RR - 1)));
  EXPECT_NEAR(f.x, expected, 1e-6);
  EXPECT_NEAR(pdf, 0.7 / kPi, 1e-6);
}

TEST(NodeClosures, SheenIsSchlicksWeightOfTheHalfAngle) {
  const Vec3f I = direction(0.5, 0.0), L = direction(0.8, 1.0);
  PrincipledInputs in;
  in.base_color = {0.8f, 0.4f, 0.2f};
  in.sheen = 0.7f;
  in.sheen_tint = 0.5f;
  Surface s = surface(I);
  s.add_principled(in, {1.f, 1.f, 1.f});
  const Closure* c = find(s, ClosureType::kPrincipledSheen);
  ASSERT_NE(c, nullptr);
  float pdf;
  const Rgb f = closure_eval(*c, {I, {0, 0, 1}, {0, 0, 1}}, L, pdf);
  const double LdotH = dot(Vec3d(L), Vec3d(normalize(L + I)));
  EXPECT_NEAR(f.x, std::pow(1 - LdotH, 5) * 0.8, 1e-6);
  // Colour: white mixed with the base over its Rec. 709 luminance, by Sheen Tint.
  const double lum = 0.2126 * 0.8 + 0.7152 * 0.4 + 0.0722 * 0.2;
  EXPECT_NEAR(c->weight.x, 0.7 * (0.5 + 0.5 * 0.8 / lum), 1e-5);
  EXPECT_NEAR(c->weight.z, 0.7 * (0.5 + 0.5 * 0.2 / lum), 1e-5);
  // The sample weight is scaled by the lobe's value at H = N: (1 - N.I)^5 N.I.
  EXPECT_NEAR(c->sample_weight,
              (c->weight.x + c->weight.y + c->weight.z) / 3 * std::pow(0.5, 5) * 0.5, 1e-6);
}

TEST(NodeClosures, FresnelColourInterpolatesBetweenCspec0AndWhite) {
  const Rgb cspec0{0.9f, 0.5f, 0.1f};
  for (double c : {1.0, 0.8, 0.4, 0.1}) {
    const double F0 = fresnel_exact(1.0, 1.5), F = fresnel_exact(c, 1.5);
    const double t = (F - F0) / (1 - F0);
    const Rgb got = interpolate_fresnel_color(direction(c, 0.0), {0.f, 0.f, 1.f}, 1.5f,
                                              fresnel_dielectric_cos(1.f, 1.5f), cspec0);
    EXPECT_NEAR(got.y, 0.5 * (1 - t) + t, 1e-5) << c;
    EXPECT_NEAR(fresnel_dielectric_cos(float(c), 1.5f), F, 1e-6) << c;
  }
}

// svm_closure.h: the specular lobe's index gives F0 = 0.08 specular; cspec0 mixes the tinted
// dielectric F0 (tint: the base over 0.3 r + 0.6 g + 0.1 b) into the base by metallic.
TEST(NodeClosures, PrincipledSpecularLayer) {
  PrincipledInputs in;
  in.base_color = {0.8f, 0.3f, 0.1f};
  in.specular = 0.5f;
  in.specular_tint = 1.f;
  in.metallic = 0.25f;
  in.roughness = 0.4f;
  in.anisotropic = 0.5f;
  in.tangent = {1.f, 0.f, 0.f};
  Surface s = surface(direction(0.6, 0.0));
  s.add_principled(in, {1.f, 1.f, 1.f});
  const Closure* c = find(s, ClosureType::kMicrofacetReflect);
  ASSERT_NE(c, nullptr);
  EXPECT_NEAR(fresnel_dielectric_cos(1.f, c->microfacet.ior), 0.04, 1e-6);
  const double lum = 0.3 * 0.8 + 0.6 * 0.3 + 0.1 * 0.1;
  EXPECT_NEAR(c->microfacet.cspec0.x, 0.04 * 0.8 / lum * 0.75 + 0.8 * 0.25, 1e-6);
  EXPECT_NEAR(c->microfacet.cspec0.z, 0.04 * 0.1 / lum * 0.75 + 0.1 * 0.25, 1e-6);
  const double aspect = std::sqrt(1 - 0.5 * 0.9);
  EXPECT_NEAR(c->microfacet.alpha_x, 0.16 / aspect, 1e-6);
  EXPECT_NEAR(c->microfacet.alpha_y, 0.16 * aspect, 1e-6);
  EXPECT_NEAR(c->weight.x, 1.0, 1e-6);  // 1 - final transmission
}

// Multiscatter GGX only above roughness 0.075 (svm_closure.h), the glass split by the Fresnel
// factor at the normal, Transmission Roughness only with GGX.
TEST(NodeClosures, PrincipledDistributionAndTransmission) {
  const Vec3f I = direction(0.7, 0.0);
  PrincipledInputs in;
  in.distribution = Distribution::kMultiGgx;
  in.roughness = 0.07f;
  Surface s = surface(I);
  s.add_principled(in, {1.f, 1.f, 1.f});
  EXPECT_NE(find(s, ClosureType::kMicrofacetReflect), nullptr);
  in.roughness = 0.08f;
  s = surface(I);
  s.add_principled(in, {1.f, 1.f, 1.f});
  EXPECT_NE(find(s, ClosureType::kMultiGgxReflect), nullptr);

  in = {};
  in.metallic = 0.2f;
  in.transmission = 0.5f;
  in.roughness = 0.3f;
  in.transmission_roughness = 0.5f;
  in.ior = 1.5f;
  s = surface(I);
  s.add_principled(in, {1.f, 1.f, 1.f});
  const Closure* diffuse = find(s, ClosureType::kPrincipledDiffuse);
  const Closure* refraction = find(s, ClosureType::kMicrofacetRefract);
  ASSERT_NE(diffuse, nullptr);
  ASSERT_NE(refraction, nullptr);
  EXPECT_NEAR(diffuse->weight.x, 0.8 * 0.8 * 0.5, 1e-6);
  const double F = fresnel_exact(0.7, 1.5);
  EXPECT_NEAR(refraction->weight.x, 0.8 * 0.5 * 0.8 * (1 - F), 1e-5);
  const double rough = 1 - 0.7 * 0.5;
  EXPECT_NEAR(refraction->microfacet.alpha_x, rough * rough, 1e-6);
  in.distribution = Distribution::kMultiGgx;
  s = surface(I);
  s.add_principled(in, {1.f, 1.f, 1.f});
  EXPECT_NE(find(s, ClosureType::kMultiGgxGlass), nullptr);
  EXPECT_EQ(find(s, ClosureType::kMicrofacetRefract), nullptr);
}

// Beyond kMaxClosures the lightest closure goes, whatever the order they came in.
TEST(NodeClosures, FullSurfaceDropsTheLightestClosure) {
  Surface s = surface(direction(0.5, 0.0));
  for (int i = 0; i < Surface::kMaxClosures + 4; ++i) {
    const float w = float((i * 7) % (Surface::kMaxClosures + 4) + 1);
    s.add_diffuse({w, w, w}, 0.f, {}, {1.f, 1.f, 1.f});
  }
  ASSERT_EQ(s.closure_count(), Surface::kMaxClosures);
  float lightest = 1e9f;
  for (int i = 0; i < s.closure_count(); ++i)
    lightest = std::min(lightest, s.closure(i).sample_weight);
  EXPECT_EQ(lightest, 5.f);  // weights 1..20: 1 to 4 dropped
}

// Back faces: the node's normal (front side) is turned to the ray's side, and the glass index
// inverts.
TEST(NodeClosures, BackFacesTurnTheNormalAndInvertTheIndex) {
  Surface s;
  const Vec3f I = direction(0.8, 0.3);
  s.begin({I, {0.f, 0.f, 1.f}, {0.f, 0.f, 1.f}, true});
  s.add_glass(Distribution::kGgx, {1.f, 1.f, 1.f}, 0.3f, 1.5f, {0.f, 0.f, -1.f}, {1.f, 1.f, 1.f});
  const Closure* r = find(s, ClosureType::kMicrofacetRefract);
  ASSERT_NE(r, nullptr);
  EXPECT_NEAR(r->N.z, 1.f, 1e-6);
  EXPECT_NEAR(r->microfacet.ior, 1 / 1.5, 1e-6);
}

}  // namespace
}  // namespace fb
