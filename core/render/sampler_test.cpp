#include "core/render/sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace fb {
namespace {

std::vector<Vec2f> pixel_points(const PixelSampler& sampler, uint32_t count, uint32_t x = 3,
                                uint32_t y = 7, uint32_t dimension = kLensDimension) {
  std::vector<Vec2f> points;
  for (uint32_t s = 0; s < count; ++s)
    points.push_back(sampler.get_2d({x, y, s, dimension}));
  return points;
}

// A (0,k,2)-net in base 2: every elementary interval [a/2^i, (a+1)/2^i) x [b/2^j, (b+1)/2^j) with
// i + j = k holds exactly one of the 2^k points.
TEST(PixelSampler, PowerOfTwoCountsAreZeroTwoNets) {
  const PixelSampler sampler(42);
  for (uint32_t k = 1; k <= 10; ++k) {
    const std::vector<Vec2f> points = pixel_points(sampler, 1u << k);
    for (uint32_t i = 0; i <= k; ++i) {
      std::set<std::pair<uint32_t, uint32_t>> cells;
      for (const Vec2f& p : points)
        cells.insert({uint32_t(p.x * float(1u << i)), uint32_t(p.y * float(1u << (k - i)))});
      EXPECT_EQ(cells.size(), size_t(1) << k) << "k = " << k << ", x split in 2^" << i;
    }
  }
}

TEST(PixelSampler, OneDimensionIsStratified) {
  const PixelSampler sampler(1);
  for (uint32_t k = 1; k <= 10; ++k) {
    std::set<uint32_t> strata;
    for (uint32_t s = 0; s < (1u << k); ++s)
      strata.insert(uint32_t(sampler.get_1d({5, 9, s, kTimeDimension}) * float(1u << k)));
    EXPECT_EQ(strata.size(), size_t(1) << k) << "k = " << k;
  }
}

TEST(PixelSampler, ValuesAreRepeatableOnTheGridAndDifferPerPixelAndPair) {
  const PixelSampler a(7), b(7), other_seed(8);
  for (uint32_t s = 0; s < 64; ++s) {
    const Vec2f p = a.get_2d({1, 2, s, kFilterDimension});
    const Vec2f q = b.get_2d({1, 2, s, kFilterDimension});
    EXPECT_EQ(p.x, q.x);
    EXPECT_EQ(p.y, q.y);
    for (float v : {p.x, p.y, a.get({1, 2, s, 9}), a.get_1d({1, 2, s, kTimeDimension})}) {
      EXPECT_GE(v, 0.f);
      EXPECT_LT(v, 1.f);
      EXPECT_EQ(v * 0x1p24f, std::floor(v * 0x1p24f));  // a multiple of 2^-24 (plugin_abi.h)
    }
  }
  // Scrambles are per pixel, per pair and per seed: the same sample index lands elsewhere.
  const auto differs = [](Vec2f p, Vec2f q) { return p.x != q.x || p.y != q.y; };
  EXPECT_TRUE(
      differs(a.get_2d({1, 2, 0, kFilterDimension}), a.get_2d({2, 2, 0, kFilterDimension})));
  EXPECT_TRUE(differs(a.get_2d({1, 2, 0, kFilterDimension}), a.get_2d({1, 2, 0, kLensDimension})));
  EXPECT_TRUE(differs(a.get_2d({1, 2, 0, kFilterDimension}),
                      other_seed.get_2d({1, 2, 0, kFilterDimension})));
}

// Any count, not only powers of two, is an unbiased estimate: over many pixels the mean of the
// first 37 points of a pixel is 1/2 per axis and the mean of x*y is 1/4 (no correlation).
TEST(PixelSampler, NonPowerOfTwoCountsAreUnbiased) {
  const PixelSampler sampler(3);
  double sum_x = 0, sum_y = 0, sum_xy = 0;
  uint32_t n = 0;
  for (uint32_t pixel = 0; pixel < 4000; ++pixel)
    for (const Vec2f& p : pixel_points(sampler, 37, pixel % 64, pixel / 64)) {
      sum_x += p.x, sum_y += p.y, sum_xy += double(p.x) * p.y, ++n;
    }
  // Independent uniform points would give a standard error of 1/sqrt(12 n) ~ 0.0007 per mean.
  EXPECT_NEAR(sum_x / n, 0.5, 0.003);
  EXPECT_NEAR(sum_y / n, 0.5, 0.003);
  EXPECT_NEAR(sum_xy / n, 0.25, 0.003);
}

}  // namespace
}  // namespace fb
