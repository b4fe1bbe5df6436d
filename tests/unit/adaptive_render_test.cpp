// Adaptive sampling (core/film/adaptive_sampling.h) through whole renders: converged pixels stop
// taking samples (counted per pixel in the film), no pixel stops before the minimum, the image's
// mean stays the unbiased one within the noise of the renders compared, and the image stays
// bit-identical for any thread count. Cycles' derived settings are checked against the numbers
// its integrator.cpp states.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numeric>

#include "core/film/adaptive_sampling.h"
#include "core/render/render_job.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::GltfBuilder;

std::vector<Vec3f> quad(float x0, float x1, float y0, float y1, float z) {
  return {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
}
const std::vector<uint32_t> kQuad = {0, 1, 2, 0, 2, 3};

// The view's left half is an emissive wall: every sample of its pixels has the same value, so
// their error is 0 and they converge at the first check. The right half is a grey wall lit by a
// small square lamp in front of it: light sampling leaves noise there.
Scene half_noisy_scene() {
  GltfBuilder gltf;
  GltfBuilder::Node glow, grey, lamp, camera;
  glow.mesh = gltf.mesh(quad(-50, 0, -50, 50, -5), kQuad, gltf.material({0, 0, 0}, {1, 1, 1}));
  grey.mesh = gltf.mesh(quad(0, 50, -50, 50, -5), kQuad, gltf.material({0.8f, 0.8f, 0.8f}));
  lamp.mesh = gltf.mesh(quad(-0.15f, 0.15f, -0.15f, 0.15f, 0), kQuad,
                        gltf.material({0, 0, 0}, {1, 1, 1}, 40.0));
  lamp.translation = {1.2, 0.4, -4.2};
  camera.camera = gltf.perspective_camera(0.8, 1.5, 0.01, 100);
  gltf.node(glow), gltf.node(grey), gltf.node(lamp), gltf.node(camera);
  Diagnostics diagnostics;
  return import_gltf(gltf.write(test::scratch_dir() / "half_noisy.gltf"), diagnostics);
}

struct Rendered {
  Image image;
  std::vector<uint32_t> counts;  // per pixel
  uint64_t samples = 0;
};

Rendered render(const Scene& scene, uint32_t spp, uint64_t seed, double threshold,
                uint32_t min_samples = 0) {
  RenderOptions options;
  options.width = 36, options.height = 24, options.samples_per_pixel = spp, options.seed = seed;
  options.filter = "box";
  options.adaptive_threshold = threshold;
  options.adaptive_min_samples = min_samples;
  options.show_progress = false;
  const RenderJob job(scene, options, test::loader());
  Film film = job.make_film();
  const RenderResult result = job.run(film);
  EXPECT_EQ(result.stats.dropped_samples, 0u);
  return {result.image,
          std::vector<uint32_t>(film.sample_counts(), film.sample_counts() + film.pixel_count()),
          result.stats.samples};
}

double mean_green(const Image& image) {
  double sum = 0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      sum += image.at(x, y, 1);
  return sum / (double(image.width) * image.height);
}

TEST(AdaptiveSampling, DerivesCyclesSettings) {
  EXPECT_FALSE(adaptive_settings({0, 0}));
  // integrator.cpp: "Threshold 0.1 -> 32, 0.01 -> 64, 0.001 -> 128", and the factor 5.
  EXPECT_EQ(adaptive_settings({0.1, 0})->min_samples, 32u);
  EXPECT_EQ(adaptive_settings({0.01, 0})->min_samples, 64u);
  EXPECT_EQ(adaptive_settings({0.001, 0})->min_samples, 128u);
  EXPECT_EQ(adaptive_settings({0.01, 2})->min_samples, 4u);  // at least 4
  EXPECT_EQ(adaptive_settings({0.01, 40})->min_samples, 40u);
  EXPECT_DOUBLE_EQ(adaptive_settings({0.01, 0})->threshold, 0.05);
}

// |I - A| / sqrt(I) on a film of two pixels: one whose samples alternate (its half buffer, the odd
// samples, differs from the whole mean), one constant.
TEST(AdaptiveSampling, ErrorIsTheHalfBufferDifferenceOverTheSquareRootOfIntensity) {
  Film film(2, 1, {"R", "G", "B"});
  ConvergenceMap map(2, 1, *adaptive_settings({0.01, 4}), 1.0);
  for (uint32_t s = 0; s < 4; ++s) {
    const float v = s % 2 ? 0.3f : 0.1f, constant[3] = {0.2f, 0.2f, 0.2f};
    const float alternating[3] = {v, v, v};
    film.add(0, 0, alternating, 1), map.add(0, 0, s, alternating, 1);
    film.add(1, 0, constant, 1), map.add(1, 0, s, constant, 1);
  }
  // I = 0.2 per channel, A = 0.3: 3 * 0.1 / sqrt(0.6).
  EXPECT_NEAR(map.error(film, 0, 0), 0.3 / (1e-4 + std::sqrt(0.6)), 1e-6);
  EXPECT_NEAR(map.error(film, 1, 0), 0.0, 1e-7);
  // The constant pixel is below the threshold but its neighbour is not: both go on sampling.
  map.update(film, 4, [](uint32_t, uint32_t) { ADD_FAILURE() << "nothing should converge"; });
  EXPECT_FALSE(map.converged(1, 0));
}

TEST(AdaptiveSampling, ConvergedPixelsStopAndMinimumSamplesAreHonoured) {
  const Scene scene = half_noisy_scene();
  const uint32_t spp = 128, min_samples = 40;
  const Rendered r = render(scene, spp, 3, 0.01, min_samples);
  const uint64_t counted = std::accumulate(r.counts.begin(), r.counts.end(), uint64_t(0));
  EXPECT_EQ(counted, r.samples) << "the film's per-pixel counts are the samples taken";
  // The first check comes at the first multiple of 16 from the minimum on.
  const uint32_t first_check = 48;
  for (uint32_t y = 0; y < 24; ++y) {
    // Deep inside the emissive half (away from the noisy half's reach of one pixel): converged
    // at the first check.
    for (uint32_t x = 0; x < 15; ++x)
      EXPECT_EQ(r.counts[y * 36 + x], first_check) << x << "," << y;
    for (uint32_t x = 0; x < 36; ++x)
      EXPECT_GE(r.counts[y * 36 + x], first_check);
  }
  const uint32_t most = *std::max_element(r.counts.begin(), r.counts.end());
  EXPECT_EQ(most, spp) << "the lamp's noisy pixels should take every sample";
  EXPECT_LT(r.samples, uint64_t(36) * 24 * spp * 3 / 4);
  for (uint32_t y = 0; y < 24; ++y)
    for (uint32_t x = 0; x < 18; ++x)
      ASSERT_NEAR(r.image.at(x, y, 1), 1.0f, 1e-6f);
}

// The image mean of an adaptive render against the mean of two independent full renders: within
// 4 sigma of the noise of both, the noise measured per pixel from the full renders' difference
// (a pixel's variance per sample is (I1 - I2)^2 / 2 * N, divided by its own count). With Cycles'
// automatic minimum (64 samples here). A much lower minimum is biased on this scene: a pixel at
// the lamp's edge whose first samples all miss the lamp has I = A and stops dark (minimum 16:
// the mean 2.4 % low over 8 seeds; automatic: 0.3 % low, within the noise; docs/sampling.md).
TEST(AdaptiveSampling, ImageMeanStaysUnbiasedWithinNoise) {
  const Scene scene = half_noisy_scene();
  const uint32_t spp = 256;
  const Rendered full[2] = {render(scene, spp, 1, 0), render(scene, spp, 2, 0)};
  const Rendered adaptive = render(scene, spp, 3, 0.02);
  ASSERT_LT(adaptive.samples, full[0].samples * 3 / 4) << "the threshold should stop pixels";
  const size_t pixels = full[0].counts.size();
  double variance_full = 0, variance_adaptive = 0;
  for (size_t i = 0; i < pixels; ++i) {
    const double d = full[0].image.pixels[i * 3 + 1] - full[1].image.pixels[i * 3 + 1];
    const double per_sample = d * d / 2 * spp;
    variance_full += per_sample / (2 * spp);  // the mean of the two renders
    variance_adaptive += per_sample / adaptive.counts[i];
  }
  const double sigma = std::sqrt(variance_full + variance_adaptive) / double(pixels);
  const double reference = (mean_green(full[0].image) + mean_green(full[1].image)) / 2;
  const double difference = mean_green(adaptive.image) - reference;
  std::printf("image mean %.6f, adaptive %.6f: difference %.2g, sigma %.2g\n", reference,
              reference + difference, difference, sigma);
  EXPECT_GT(sigma, 0.0);
  EXPECT_LT(std::abs(difference), 4 * sigma);
}

TEST(AdaptiveSampling, ImageIsBitIdenticalForAnyThreadCount) {
  const Scene scene = half_noisy_scene();
  std::vector<float> pixels[2];
  std::vector<uint32_t> counts[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    const Rendered r = render(scene, 64, 5, 0.02, 16);
    pixels[threads - 1] = r.image.pixels, counts[threads - 1] = r.counts;
  }
  EXPECT_EQ(pixels[0], pixels[1]);
  EXPECT_EQ(counts[0], counts[1]);
}

// The command line's values replace the shot's; a shot with adaptive sampling on and threshold 0
// gets Cycles' automatic max(0.001, 1 / spp).
TEST(AdaptiveSampling, ShotSettingsAndOptionsChooseIt) {
  Scene scene = half_noisy_scene();
  RenderOptions options;
  options.samples_per_pixel = 256;
  EXPECT_FALSE(plan_shot(scene, options).adaptive) << "off unless asked";
  scene.settings.adaptive = ShotAdaptiveSampling{true, 0, 0};
  const ShotPlan automatic = plan_shot(scene, options);
  ASSERT_TRUE(automatic.adaptive);
  EXPECT_DOUBLE_EQ(automatic.adaptive_request.threshold, 1.0 / 256);
  EXPECT_EQ(automatic.adaptive->min_samples, uint32_t(std::ceil(16 / std::pow(1.0 / 256, 0.3))));
  options.adaptive_min_samples = 100;
  EXPECT_EQ(plan_shot(scene, options).adaptive->min_samples, 100u);
  options.adaptive_threshold = 0;
  EXPECT_FALSE(plan_shot(scene, options).adaptive) << "--adaptive-threshold 0 turns it off";
  scene.settings.adaptive->use = false;
  options.adaptive_threshold.reset();
  EXPECT_FALSE(plan_shot(scene, options).adaptive);
}

TEST(AdaptiveSampling, SplatReconstructionIsRefused) {
  const Scene scene = half_noisy_scene();
  RenderOptions options;
  options.adaptive_threshold = 0.01;
  options.reconstruction = Reconstruction::kSplat;
  try {
    const RenderJob job(scene, options, test::loader());
    FAIL() << "expected a UsageError";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--reconstruction importance"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace fb
