#include "core/film/film.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fb {
namespace {

TEST(Film, ResolvesTheFilterWeightedMean) {
  Film film(2, 1, {"R", "G", "B"});
  const float a[3] = {1, 2, 3}, b[3] = {3, 2, 1};
  EXPECT_TRUE(film.add(0, 0, a, 1.f));
  EXPECT_TRUE(film.add(0, 0, b, 3.f));
  const Image image = film.resolve();
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), (1 * 1 + 3 * 3) / 4.f);
  EXPECT_FLOAT_EQ(image.at(0, 0, 2), (3 * 1 + 1 * 3) / 4.f);
  EXPECT_EQ(image.at(1, 0, 0), 0.f);  // no sample: zero, not NaN
}

TEST(Film, NegativeLobeWeightsKeepTheirSign) {
  Film film(1, 1, {"R", "G", "B"});
  const float bright[3] = {10, 10, 10}, dark[3] = {0, 0, 0};
  film.add(0, 0, bright, -0.25f);
  film.add(0, 0, dark, 1.25f);
  EXPECT_FLOAT_EQ(film.resolve().at(0, 0, 0), -2.5f);
}

TEST(Film, DropsNonFiniteSamplesWhole) {
  Film film(1, 1, {"R", "G", "B"});
  const float good[3] = {1, 1, 1};
  const float nan[3] = {1, std::numeric_limits<float>::quiet_NaN(), 1};
  const float inf[3] = {std::numeric_limits<float>::infinity(), 1, 1};
  EXPECT_TRUE(film.add(0, 0, good, 1.f));
  EXPECT_FALSE(film.add(0, 0, nan, 1.f));
  EXPECT_FALSE(film.add(0, 0, inf, 1.f));
  EXPECT_FALSE(film.add(0, 0, good, std::numeric_limits<float>::infinity()));
  const Image image = film.resolve();
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(image.at(0, 0, c), 1.f);
}

TEST(Film, ImagesAreStoredTopRowFirst) {
  Film film(3, 2, {"R", "G", "B", "Z"});
  const float v[4] = {0, 0, 0, 7};
  film.add(2, 1, v, 1.f);
  const Image image = film.resolve();
  EXPECT_EQ(image.pixels[(1 * 3 + 2) * 4 + 3], 7.f);
}

// The film's state comes from the kernel zeroed (zeroed_pages.h) instead of a zeroing pass: a
// fresh film must read as zero everywhere, in a small film and in one whose arrays are large
// enough to sit on huge pages (here 24 MB of sums), up to their last element.
TEST(Film, AFreshFilmIsZeroEverywhere) {
  for (const uint32_t side : {3u, 1000u}) {
    Film film(side, side, {"R", "G", "B"});
    const size_t pixels = film.pixel_count();
    size_t nonzero = 0;
    for (size_t i = 0; i < pixels; ++i) {
      nonzero += film.weights()[i] != 0.0 || film.sample_counts()[i] != 0;
      for (size_t c = 0; c < 3; ++c)
        nonzero += film.sums()[i * 3 + c] != 0.0;
    }
    EXPECT_EQ(nonzero, 0u) << side;
    const float v[3] = {1, 2, 3};
    EXPECT_TRUE(film.add(side - 1, side - 1, v, 2.f));
    const Image image = film.resolve();
    EXPECT_EQ(image.at(side - 1, side - 1, 2), 3.f);
    EXPECT_EQ(image.at(0, 0, 0), 0.f);
  }
}

TEST(Film, DepthPassIsTheNearestSampleNotTheMean) {
  // A pixel whose samples see a surface 2 m and 3 m away and the background (1e10 m): its depth
  // is the nearest sample's, while the other channels stay the weighted mean.
  Film film(2, 1, {"R", "G", "B", "ViewLayer.Depth.Z", "ViewLayer.Normal.Z"});
  const float near[5] = {1, 1, 1, 2, 1}, far[5] = {3, 3, 3, 3, 0}, miss[5] = {0, 0, 0, 1e10f, 0};
  EXPECT_TRUE(film.add(0, 0, far, 1.f));
  EXPECT_TRUE(film.add(0, 0, miss, 2.f));
  EXPECT_TRUE(film.add(0, 0, near, 1.f));
  const Image image = film.resolve();
  EXPECT_EQ(image.at(0, 0, 3), 2.f);
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), (3.f + 1.f) / 4.f);
  EXPECT_FLOAT_EQ(image.at(0, 0, 4), 1.f / 4.f);
  EXPECT_EQ(image.at(1, 0, 3), 0.f);  // no sample: zero, as every channel
}

}  // namespace
}  // namespace fb
