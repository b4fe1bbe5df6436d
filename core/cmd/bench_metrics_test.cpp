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
