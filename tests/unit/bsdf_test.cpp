// The glTF metallic-roughness BSDF (core/shading/gltf_bsdf.h) against the laws it must obey:
// energy conservation (white furnace), reciprocity, a density that integrates to one, and samples
// distributed as that density says (chi-square over a sphere histogram).
#include "core/shading/gltf_bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/math/constants.h"
#include "tests/support/chi_square.h"
#include "tests/support/sphere_quadrature.h"

namespace fb {
namespace {

using test::direction;
using test::sphere_integral;

struct BsdfCase {
  const char* name;
  BsdfParams params;
};

std::vector<BsdfCase> bsdf_cases() {
  std::vector<BsdfCase> out;
  for (float roughness : {0.3f, 0.6f, 1.f}) {
    out.push_back({"dielectric", {{1, 1, 1}, 0.f, roughness, 0.f, 1.5f}});
    out.push_back({"metal", {{1, 1, 1}, 1.f, roughness, 0.f, 1.5f}});
    out.push_back({"half-metal", {{0.8f, 0.5f, 0.2f}, 0.5f, roughness, 0.f, 1.5f}});
    out.push_back({"glass entering", {{1, 1, 1}, 0.f, roughness, 1.f, 1.5f}});
    out.push_back({"glass leaving", {{1, 1, 1}, 0.f, roughness, 1.f, 1 / 1.5f}});
    out.push_back({"half-transmissive", {{1, 1, 1}, 0.2f, roughness, 0.5f, 1.33f}});
  }
  return out;
}

// Quadrature fine enough for lobes of alpha >= 0.09 (roughness 0.3).
constexpr int kBsdfQuadratureSteps = 1200;

// The directional albedo, integral of f |cos| (for transmission, times eta^2 to undo radiance
// scaling), never exceeds one for a white surface. For a white metal it is the GGX
// single-scattering albedo, which loses energy at grazing angles and high roughness (half of it at
// alpha = 1) but keeps more than 95 % at normal incidence for alpha = 0.09.
TEST(Bsdf, WhiteFurnaceReflectsNoMoreThanItReceives) {
  for (const BsdfCase& k : bsdf_cases()) {
    const Bsdf bsdf(k.params);
    for (double cos_o : {1.0, 0.7, 0.3, 0.05}) {
      const Vec3f wo = direction(cos_o, 0.3);
      const double albedo = sphere_integral(kBsdfQuadratureSteps, [&](Vec3f wi) {
        const double scale = wi.z < 0 ? double(k.params.eta) * k.params.eta : 1.0;
        return double(max_component(bsdf.eval(wo, wi))) * std::abs(wi.z) * scale;
      });
      SCOPED_TRACE(std::string(k.name) + " roughness " + std::to_string(k.params.roughness) +
                   " cos_o " + std::to_string(cos_o));
      EXPECT_LE(albedo, 1.0 + 2e-3);
      if (cos_o == 1.0 && k.params.metallic == 1.f && k.params.roughness <= 0.3f) {
        EXPECT_GT(albedo, 0.95);
      }
    }
  }
}

// Lambertian limit: a dielectric's diffuse part returns base_color (1 - F)^2 / (1 - F_avg) / pi at
// normal incidence, where F = F0 = 0.04 at ior 1.5 and F_avg = F0 + (1 - F0) / 21.
TEST(Bsdf, DiffuseIsLambertianUnderTheFresnelLayer) {
  const Bsdf bsdf({{0.5f, 0.25f, 0.125f}, 0.f, 1.f, 0.f, 1.5f});
  const Vec3f wo = direction(1.0, 0), wi = direction(1.0, 0);
  const Rgb f = bsdf.eval(wo, wi);
  const Bsdf black({{0, 0, 0}, 0.f, 1.f, 0.f, 1.5f});  // the specular part alone
  const Rgb diffuse = f - black.eval(wo, wi);
  const double through = 0.96 * 0.96 / (1 - (0.04 + 0.96 / 21));
  EXPECT_NEAR(diffuse.x, 0.5 * through / kPi, 1e-6);
  EXPECT_NEAR(diffuse.z, 0.125 * through / kPi, 1e-6);
}

// Chiang et al. 2019's terminator term, as Cycles applies it to bumped diffuse lobes: no effect
// without mapping or where the light is on the unshadowed side, zero for light below the smooth
// surface, the smoothed ratio in between; and only on the diffuse part.
TEST(Bsdf, BumpShadowingDimsOnlyLightTheSmoothSurfaceHidesFromTheBump) {
  const Vec3f smooth = normalize(Vec3f{0.5f, 0.f, 1.f});        // the bump leans towards -x
  EXPECT_EQ(bump_shadowing(smooth, direction(0.9, 0.0)), 1.f);  // towards +x: g > 1
  EXPECT_EQ(bump_shadowing(smooth, normalize(Vec3f{-1.f, 0.f, 0.3f})), 0.f);  // below smooth
  const Vec3f wi = normalize(Vec3f{-1.f, 0.f, 0.8f});
  const double g = dot(smooth, wi) / (wi.z * smooth.z);
  ASSERT_GT(g, 0);
  ASSERT_LT(g, 1);
  EXPECT_NEAR(bump_shadowing(smooth, wi), g + g * g - g * g * g, 1e-6);
  const Vec3f wo = direction(1.0, 0.0);
  const Bsdf flat({{0.5f, 0.5f, 0.5f}, 0.f, 1.f, 0.f, 1.5f, 0.f});
  const Bsdf bumped({{0.5f, 0.5f, 0.5f}, 0.f, 1.f, 0.f, 1.5f, 0.f, smooth});
  EXPECT_NEAR(bumped.eval(wo, wi).x, flat.eval(wo, wi).x * bump_shadowing(smooth, wi), 1e-7);
  const Bsdf metal({{0.5f, 0.5f, 0.5f}, 1.f, 0.5f, 0.f, 1.5f, 1.f, smooth});
  const Bsdf flat_metal({{0.5f, 0.5f, 0.5f}, 1.f, 0.5f, 0.f, 1.5f, 1.f});
  EXPECT_EQ(metal.eval(wo, wi).x, flat_metal.eval(wo, wi).x);
}

TEST(Bsdf, ReflectionIsReciprocal) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (const BsdfCase& k : bsdf_cases()) {
    const Bsdf bsdf(k.params);
    for (int n = 0; n < 200; ++n) {
      const Vec3f a = direction(0.02 + 0.98 * u(rng), 2 * kPi * u(rng));
      const Vec3f b = direction(0.02 + 0.98 * u(rng), 2 * kPi * u(rng));
      const Rgb ab = bsdf.eval(a, b), ba = bsdf.eval(b, a);
      EXPECT_NEAR(ab.x, ba.x, 1e-5f * std::max(1.f, ab.x)) << k.name;
      EXPECT_NEAR(ab.z, ba.z, 1e-5f * std::max(1.f, ab.z)) << k.name;
    }
  }
}

// The density sample() draws from integrates, over both hemispheres, to the probability that
// sample() succeeds: one less the microfacet reflections that go below the surface and the
// refractions that stay above it or are totally reflected (half of all at alpha = 1).
TEST(Bsdf, PdfIntegratesToTheProbabilityOfASample) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0, 1);
  for (const BsdfCase& k : bsdf_cases()) {
    const Bsdf bsdf(k.params);
    for (double cos_o : {0.9, 0.4}) {
      const Vec3f wo = direction(cos_o, 1.1);
      const double mass =
          sphere_integral(kBsdfQuadratureSteps, [&](Vec3f wi) { return double(bsdf.pdf(wo, wi)); });
      constexpr int kN = 100000;
      int successes = 0;
      for (int n = 0; n < kN; ++n) {
        Bsdf::Sample s;
        successes += bsdf.sample(wo, u(rng), {u(rng), u(rng)}, s);
      }
      SCOPED_TRACE(std::string(k.name) + " roughness " + std::to_string(k.params.roughness) +
                   " cos_o " + std::to_string(cos_o));
      EXPECT_LE(mass, 1.0 + 3e-3);
      // Binomial standard deviation is at most 0.0016 for 1e5 samples: 4 of them, plus quadrature.
      EXPECT_NEAR(mass, double(successes) / kN, 0.0065 + 2e-3);
    }
  }
}

// Pearson's chi-square between a histogram of sampled directions over (cos theta, phi) cells of
// the whole sphere and the pdf integrated over each cell; cells with tiny expectation are pooled,
// as in Mitsuba's chi2 tests. The threshold is the 1e-3 quantile's upper tail for ~200 degrees of
// freedom, so a correct sampler fails once in a thousand runs at most (the seed is fixed anyway).
TEST(Bsdf, SamplesFollowThePdf) {
  constexpr int kTheta = 20, kPhi = 40, kSamples = 400000;
  for (const BsdfCase& k : bsdf_cases()) {
    const Bsdf bsdf(k.params);
    const Vec3f wo = direction(0.6, 0.4);
    std::vector<double> observed(kTheta * kPhi, 0), expected(kTheta * kPhi, 0);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0, 1);
    for (int n = 0; n < kSamples; ++n) {
      Bsdf::Sample s;
      if (!bsdf.sample(wo, u(rng), {u(rng), u(rng)}, s)) continue;
      // The reported pdf and weight agree with pdf() and eval().
      ASSERT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 1e-3f * s.pdf);
      const int i = std::clamp(int((s.wi.z + 1) / 2 * kTheta), 0, kTheta - 1);
      double phi = std::atan2(double(s.wi.y), double(s.wi.x));
      if (phi < 0) phi += 2 * kPi;
      const int j = std::clamp(int(phi / (2 * kPi) * kPhi), 0, kPhi - 1);
      observed[i * kPhi + j] += 1;
    }
    constexpr int kSub = 24;  // quadrature points per cell side
    for (int i = 0; i < kTheta; ++i)
      for (int j = 0; j < kPhi; ++j) {
        double sum = 0;
        for (int a = 0; a < kSub; ++a)
          for (int b = 0; b < kSub; ++b) {
            const double c = -1 + (i + (a + 0.5) / kSub) * 2.0 / kTheta;
            const double phi = (j + (b + 0.5) / kSub) * 2 * kPi / kPhi;
            sum += bsdf.pdf(wo, direction(c, phi));
          }
        expected[i * kPhi + j] = sum / (kSub * kSub) * (2.0 / kTheta) * (2 * kPi / kPhi) * kSamples;
      }
    const test::ChiSquare chi2 = test::chi_square(observed, expected);
    EXPECT_LT(chi2.statistic, chi2.limit()) << k.name << " roughness " << k.params.roughness << ", "
                                            << chi2.dof << " degrees of freedom";
  }
}

// The estimator sample().weight has the albedo as its mean: importance sampling is consistent with
// eval() (the furnace again, by Monte Carlo).
TEST(Bsdf, SampleWeightsAverageToTheAlbedo) {
  for (const BsdfCase& k : bsdf_cases()) {
    const Bsdf bsdf(k.params);
    const Vec3f wo = direction(0.5, 0.2);
    const double albedo = sphere_integral(
        800, [&](Vec3f wi) { return double(bsdf.eval(wo, wi).y) * std::abs(wi.z); });
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    double sum = 0;
    constexpr int kN = 200000;
    for (int n = 0; n < kN; ++n) {
      Bsdf::Sample s;
      if (bsdf.sample(wo, u(rng), {u(rng), u(rng)}, s)) sum += s.weight.y;
    }
    EXPECT_NEAR(sum / kN, albedo, 0.01 * albedo + 1e-3)
        << k.name << " roughness " << k.params.roughness;
  }
}

}  // namespace
}  // namespace fb
