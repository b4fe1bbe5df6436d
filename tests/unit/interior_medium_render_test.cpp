// Interior media (POV-Ray's `media` in an object's interior, docs/pov.md "Media") against closed
// forms: the homogeneous segment and the free flight of filmback/interior_media.h, then both
// integrators through a glowing, absorbing sphere and an absorbing slab over a glowing wall (`path`
// the radiative transfer's exact solution, `povray` the left Riemann sum POV-Ray 3.7 computes),
// and the `path` integrator's scattering in a white furnace, where it must give back the world's
// radiance exactly.
#include <gtest/gtest.h>

#include <filmback/interior_media.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/render/render_job.h"
#include "importers/pov/pov_importer.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

// Midpoint quadrature of the emission dimmed on its way, against the closed form.
TEST(InteriorMedia, HomogeneousSegmentIsTheIntegralOfItsEmission) {
  const Rgb sigma{0.f, 0.7f, 3.f}, emission{0.5f, 1.f, 2.f};
  const float length = 1.3f;
  const HomogeneousSegment segment = homogeneous_segment(sigma, emission, length);
  constexpr int kSteps = 20000;
  for (int c = 0; c < 3; ++c) {
    double integral = 0;
    for (int i = 0; i < kSteps; ++i)
      integral += emission[c] * std::exp(-sigma[c] * (i + 0.5) * length / kSteps);
    integral *= length / kSteps;
    EXPECT_NEAR(segment.emitted[c], integral, 1e-5 * integral) << c;
    EXPECT_NEAR(segment.transmittance[c], std::exp(-sigma[c] * length), 1e-7) << c;
  }
}

// Averaged over u, the free flight's weights are what they estimate: past the segment the
// transmittance e^-(sigma_t d), and at collisions the integral of sigma_s e^-(sigma_t s) ds over
// the segment (the light scattered once, for a uniform light of 1).
TEST(InteriorMedia, FreeFlightWeightsAreUnbiased) {
  const Rgb sigma_t{0.5f, 1.f, 2.f}, sigma_s{0.25f, 0.8f, 1.f};
  const float length = 1.5f;
  constexpr int kFlights = 200000;
  double passed[3] = {}, scattered[3] = {};
  for (int i = 0; i < kFlights; ++i) {
    const FreeFlight flight = free_flight(sigma_t, sigma_s, length, (i + 0.5f) / kFlights);
    for (int c = 0; c < 3; ++c)
      (flight.collided ? scattered : passed)[c] += flight.weight[c];
  }
  for (int c = 0; c < 3; ++c) {
    const double through = std::exp(-sigma_t[c] * length);
    EXPECT_NEAR(passed[c] / kFlights, through, 1e-3) << c;
    EXPECT_NEAR(scattered[c] / kFlights, sigma_s[c] * (1 - through) / sigma_t[c], 1e-3) << c;
  }
}

constexpr uint32_t kMediumShotSize = 33;  // odd: the middle pixel's centre is on the axis
constexpr double kMediumCameraDistance = 5;
constexpr int kPovRayDefaultMediaPoints = 6;  // max(2, samples / 2 + 1), samples 10

// What a segment of length d sends along a ray: exactly (`path`), or as POV-Ray 3.7 sums it,
// sum over k < N of emission e^-(sigma k d / N) d / N (`povray`, docs/pov.md "Media"). Float
// sums, compared to 1e-4.
HomogeneousSegment expected_segment(const char* integrator, Rgb sigma, Rgb emission, float d) {
  HomogeneousSegment exact = homogeneous_segment(sigma, emission, d);
  if (std::string(integrator) != "povray") return exact;
  float sum[3] = {};
  for (int k = 0; k < kPovRayDefaultMediaPoints; ++k)
    for (int c = 0; c < 3; ++c)
      sum[c] += emission[c] * std::exp(-sigma[c] * d * k / kPovRayDefaultMediaPoints) * d /
                kPovRayDefaultMediaPoints;
  return {exact.transmittance, Rgb(sum)};
}

// A .pov scene (camera on -z looking at the origin, 20 degrees wide, square) rendered through the
// pixel centres with `integrator`.
Image render_pov(const std::string& name, const std::string& sdl, const char* integrator,
                 uint32_t samples = 1) {
  const std::filesystem::path file = test::scratch_dir() / (name + ".pov");
  std::ofstream(file) << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n"
                      << "camera { location <0, 0, -" << kMediumCameraDistance
                      << "> right x up y look_at 0 angle 20 }\n"
                      << sdl;
  Diagnostics diagnostics;
  ImportOptions import;
  import.resolution = {kMediumShotSize, kMediumShotSize};
  const Scene scene = import_pov(file, import, diagnostics);
  RenderOptions options;
  options.width = options.height = kMediumShotSize;
  options.samples_per_pixel = samples;
  options.filter = "box:radius=0.001";
  options.integrator = integrator;
  options.show_progress = false;
  return RenderJob(scene, options, test::loader()).run().image;
}

// The middle pixel looks through the sphere's centre, 2 r of medium: L = e (1 - e^-(sigma 2r)) /
// sigma, POV-Ray's emission being radiance per unit of length (POV-Ray's own sum for `povray`).
TEST(InteriorMedia, GlowingSphereThroughItsCentreIsTheClosedForm) {
  const char* sdl =
      "background { rgb 0 }\n"
      "sphere { 0, 1 hollow pigment { rgbt 1 } finish { ambient 0 diffuse 0 }\n"
      "  interior { media { emission rgb <0.6, 0.4, 0.2> absorption rgb <0, 0.5, 2> } } }\n";
  const Rgb emission{0.6f, 0.4f, 0.2f}, absorption{0.f, 0.5f, 2.f};
  for (const char* integrator : {"povray", "path:max_depth=4"}) {
    const HomogeneousSegment expected = expected_segment(integrator, absorption, emission, 2.f);
    const Image image = render_pov("glowing_sphere", sdl, integrator);
    const uint32_t middle = kMediumShotSize / 2;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(image.at(middle, middle, c), expected.emitted[c], 1e-4 * expected.emitted[c])
          << integrator << " channel " << c;
    EXPECT_EQ(image.at(0, 0, 0), 0.f) << integrator;  // past the sphere: the black background
  }
}

// A slab of absorbing, glowing medium 1 m thick before a wall that glows 1: a ray at angle theta
// to the axis crosses d = 1 / cos(theta) of it, L = e^-(sigma d) + e (1 - e^-(sigma d)) / sigma.
TEST(InteriorMedia, SlabOverAGlowingWallIsTheClosedForm) {
  const char* sdl =
      "background { rgb 0 }\n"
      "plane { z, 3 pigment { rgb 1 } finish { ambient 1 diffuse 0 } }\n"
      "box { <-5, -5, -0.5>, <5, 5, 0.5> hollow pigment { rgbt 1 } finish { ambient 0 diffuse 0 }\n"
      "  interior { media { absorption rgb <0.2, 1, 3> emission rgb <0.1, 0, 0.3> } } }\n";
  const Rgb absorption{0.2f, 1.f, 3.f}, emission{0.1f, 0.f, 0.3f};
  const double per_pixel = 2 * std::tan(10.0 * std::numbers::pi / 180) / kMediumShotSize;
  for (const char* integrator : {"povray", "path:max_depth=4"}) {
    const Image image = render_pov("absorbing_slab", sdl, integrator);
    for (uint32_t i : {16u, 25u, 2u}) {
      const uint32_t j = 16;
      const double x = (i + 0.5 - kMediumShotSize / 2.0) * per_pixel;
      const float d = float(std::sqrt(1 + x * x));
      const HomogeneousSegment expected = expected_segment(integrator, absorption, emission, d);
      for (int c = 0; c < 3; ++c) {
        const double L = expected.transmittance[c] + expected.emitted[c];
        EXPECT_NEAR(image.at(i, j, c), L, 1e-4 * L) << integrator << " " << i << " channel " << c;
      }
    }
  }
}

// A sphere of medium that only scatters, in a white world of radiance 1: every path leaves it
// sooner or later (its weight stays 1: grey, no absorption), so every pixel is exactly 1 with the
// `path` integrator, whatever the number of bounces inside.
TEST(InteriorMedia, ScatteringSphereInAWhiteFurnaceIsInvisible) {
  const char* sdl =
      "background { rgb 1 }\n"
      "sphere { 0, 1 hollow pigment { rgbt 1 } finish { ambient 0 diffuse 0 }\n"
      "  interior { media { scattering { 1, rgb 1.5 } } } }\n";
  const Image image = render_pov("furnace_sphere", sdl, "path:max_depth=1000", 4);
  for (uint32_t j = 0; j < kMediumShotSize; j += 4)
    for (uint32_t i = 0; i < kMediumShotSize; i += 4)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(image.at(i, j, c), 1.f, 1e-4) << i << "," << j;
}

}  // namespace
}  // namespace fb
