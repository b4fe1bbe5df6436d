#include "core/cmd/bench_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/util/error.h"

namespace fb {
namespace {

Image rgb_image(uint32_t width, uint32_t height, float value) {
  return {width, height, {"R", "G", "B"}, std::vector<float>(size_t(width) * height * 3, value)};
}

TEST(BenchMetrics, ErrorsFollowTheirDefinitions) {
  Image reference = rgb_image(2, 1, 1.f), image = rgb_image(2, 1, 1.f);
  reference.pixels[0] = 0.f;  // red of the first pixel: r = 0, x = 1
  image.pixels[5] = 3.f;      // blue of the second: r = 1, x = 3
  const ImageError e = image_error(image, reference);
  EXPECT_DOUBLE_EQ(e.rmse, std::sqrt((1.0 + 4.0) / 6));
  EXPECT_DOUBLE_EQ(e.relmse, (1.0 / kRelMseEpsilon + 4.0 / (1 + kRelMseEpsilon)) / 6);
  EXPECT_DOUBLE_EQ(e.max_abs, 2.0);
}

TEST(BenchMetrics, ColourChannelsAreFoundByNameAndRequired) {
  Image rgba{1, 1, {"A", "B", "G", "R"}, {0.5f, 3.f, 2.f, 1.f}};
  const Image rgb = colour_channels(rgba, "x.exr");
  EXPECT_EQ(rgb.pixels, (std::vector<float>{1.f, 2.f, 3.f}));
  EXPECT_THROW(colour_channels(Image{1, 1, {"Y"}, {1.f}}, "x.exr"), InputError);
}

// The bench keeps one image per render: a render's R, G, B film image moved in is handed on, not
// copied, and two moved-in halves become the reference's mean and half difference.
TEST(BenchMetrics, MovedImagesKeepTheirPixelBuffers) {
  Image render{2, 1, {"R", "G", "B"}, {1.f, 2.f, 3.f, 4.f, 5.f, 6.f}};
  const float* render_pixels = render.pixels.data();
  const Image rgb = colour_channels(std::move(render), "render");
  EXPECT_EQ(rgb.pixels.data(), render_pixels);
  EXPECT_EQ(rgb.pixels, (std::vector<float>{1.f, 2.f, 3.f, 4.f, 5.f, 6.f}));

  Image a = rgb_image(2, 1, 3.f), b = rgb_image(2, 1, 1.f);
  const float *a_pixels = a.pixels.data(), *b_pixels = b.pixels.data();
  const AveragedReference reference = average_halves(std::move(a), std::move(b));
  EXPECT_EQ(reference.image.pixels.data(), a_pixels);
  EXPECT_EQ(reference.half_difference.pixels.data(), b_pixels);
  EXPECT_EQ(reference.image.pixels, rgb_image(2, 1, 2.f).pixels);
  EXPECT_EQ(reference.half_difference.pixels, rgb_image(2, 1, 1.f).pixels);
}

// Two references with independent noise of standard deviation s: their mean's RMSE against the
// truth is s / sqrt(2), and average_halves estimates it from their difference alone.
TEST(BenchMetrics, AveragedReferenceKnowsItsOwnNoise) {
  constexpr float kTruth = 2.f, kSigma = 0.1f;
  std::mt19937 random(7);
  std::normal_distribution<float> noise(0.f, kSigma);
  Image a = rgb_image(200, 100, kTruth), b = a;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    a.pixels[i] += noise(random), b.pixels[i] += noise(random);
  const AveragedReference reference = average_halves(a, b);
  const double actual = image_error(reference.image, rgb_image(200, 100, kTruth)).rmse;
  EXPECT_NEAR(actual, kSigma / std::sqrt(2.0), 0.01 * kSigma);
  EXPECT_NEAR(reference.noise.rmse, actual, 0.01 * kSigma);
  EXPECT_NEAR(reference.noise.relmse, actual * actual / (kTruth * kTruth + kRelMseEpsilon),
              0.05 * actual * actual / (kTruth * kTruth));
}

// The mean of halves T + d and T - d: the image T and half difference d, pixel for pixel.
AveragedReference constant_halves(const Image& truth, float d) {
  Image a = truth, b = truth;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    a.pixels[i] += d, b.pixels[i] -= d;
  return average_halves(a, b);
}

// Known halves, a known bias in one 16x16 block: every number of the agreement follows by hand.
TEST(BenchMetrics, ReferencesAgreementMeasuresTheBiasAboveBothNoises) {
  constexpr float kOurs = 0.01f, kTheirs = 0.02f, kBias = 0.16f;
  const Image truth = rgb_image(32, 32, 1.f);
  Image biased = truth;
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x)
      for (size_t c = 0; c < 3; ++c)
        biased.pixels[(size_t(y) * 32 + x) * 3 + c] += kBias;
  const AveragedReference ours = constant_halves(biased, kOurs);
  const AveragedReference theirs = constant_halves(truth, kTheirs);
  EXPECT_NEAR(ours.half_difference.pixels[7], kOurs, 1e-6);
  EXPECT_NEAR(ours.noise.rmse, kOurs, 1e-6);

  const ReferenceAgreement a = compare_references(ours, theirs);
  EXPECT_NEAR(a.between.rmse, kBias / 2, 1e-6);  // in a quarter of the pixels
  EXPECT_NEAR(a.noise_rmse, std::hypot(kOurs, kTheirs), 1e-6);
  // The twin is ours + d_ours + d_theirs: 3 % above ours everywhere, against a reference of 1.
  EXPECT_NEAR(a.comparison.noise_mean_relative, kOurs + kTheirs, 1e-6);
  EXPECT_NEAR(a.comparison.worst_noise_block, kOurs + kTheirs, 1e-6);
  EXPECT_NEAR(a.comparison.mean_relative, kBias / 4, 1e-6);
  EXPECT_NEAR(a.comparison.mean_ratio, 1 + kBias / 4, 1e-6);
  EXPECT_NEAR(a.comparison.worst_block, kBias, 1e-6);
  EXPECT_EQ(a.comparison.worst_block_x, 0u);
  // The mean (4 %) is within 2 % of its floor (3 %); the block (16 %) is not within 5 % of its.
  EXPECT_FALSE(references_agree(a));
  EXPECT_TRUE(references_agree(compare_references(constant_halves(truth, kOurs), theirs)));
}

// Unbiased references with independent Gaussian noise: the twin's difference from ours has the
// distribution of ours - theirs, so the mean relative difference equals its noise floor, both
// E|N(0, s)| / T = sqrt(2/π) s / T with s² = (σ_ours² + σ_theirs²)/2 (each mean of two halves of
// σ has variance σ²/2).
TEST(BenchMetrics, UnbiasedReferencesDifferByTheirNoiseFloor) {
  constexpr float kTruth = 2.f, kOurs = 0.1f, kTheirs = 0.05f;
  std::mt19937 random(11);
  std::normal_distribution<float> ours_noise(0.f, kOurs), theirs_noise(0.f, kTheirs);
  const Image truth = rgb_image(256, 128, kTruth);
  Image a = truth, b = truth, c = truth, d = truth;
  for (size_t i = 0; i < truth.pixels.size(); ++i) {
    a.pixels[i] += ours_noise(random), b.pixels[i] += ours_noise(random);
    c.pixels[i] += theirs_noise(random), d.pixels[i] += theirs_noise(random);
  }
  const ReferenceAgreement r = compare_references(average_halves(a, b), average_halves(c, d));
  const double s = std::sqrt((kOurs * kOurs + kTheirs * kTheirs) / 2.0);
  const double expected = std::sqrt(2 / M_PI) * s / kTruth;
  EXPECT_NEAR(r.comparison.mean_relative, expected, 0.01 * expected);
  EXPECT_NEAR(r.comparison.noise_mean_relative, expected, 0.01 * expected);
  EXPECT_NEAR(r.between.rmse, s, 0.01 * s);
  EXPECT_NEAR(r.noise_rmse, s, 0.01 * s);
  EXPECT_TRUE(references_agree(r));
}

TEST(BenchMetrics, FitRecoversAPowerLawAndInvertsIt) {
  std::vector<double> x, error;
  for (double t : {0.5, 1.0, 4.0, 16.0}) {
    x.push_back(t);
    error.push_back(0.3 * std::pow(t, -0.75));
  }
  const std::optional<LogLogFit> fit = fit_log_log(x, error);
  ASSERT_TRUE(fit);
  EXPECT_NEAR(fit->slope, -0.75, 1e-12);
  EXPECT_NEAR(std::exp(fit->intercept), 0.3, 1e-12);
  EXPECT_EQ(fit->points, 4u);
  EXPECT_NEAR(*fit->x_at(0.3 * std::pow(2.0, -0.75)), 2.0, 1e-9);
  EXPECT_FALSE(fit->extrapolates(2.0));
  EXPECT_TRUE(fit->extrapolates(20.0));
  EXPECT_FALSE(fit_log_log({1.0}, {1.0}));                       // one point
  EXPECT_FALSE(fit_log_log({1.0, 1.0}, {1.0, 0.5}));             // one time
  EXPECT_FALSE(fit_log_log({1.0, 2.0}, {1.0, 1.5})->x_at(0.5));  // not converging
}

}  // namespace
}  // namespace fb
