#include "core/image/image_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace fb {
namespace {

Image rgb_image(uint32_t width, uint32_t height, float value) {
  return {width, height, {"R", "G", "B"}, std::vector<float>(size_t(width) * height * 3, value)};
}

// Every channel of the 16x16 block whose top-left pixel is (x0, y0) set to `value`.
void fill_block(Image& image, uint32_t x0, uint32_t y0, float value) {
  for (uint32_t y = y0; y < y0 + 16; ++y)
    for (uint32_t x = x0; x < x0 + 16; ++x)
      for (size_t c = 0; c < 3; ++c)
        image.pixels[(size_t(y) * image.width + x) * 3 + c] = value;
}

// Four blocks of 1; the image is 10 % brighter in one of them, its twin 1 % brighter than the
// image everywhere: every number follows by hand.
TEST(ImageComparison, OneBrighterBlockAgainstAUniformNoiseFloor) {
  const Image reference = rgb_image(32, 32, 1.f);
  Image image = reference;
  fill_block(image, 16, 0, 1.1f);
  Image twin = image;
  for (float& v : twin.pixels)
    v += 0.01f;
  const ImageComparison c = compare_images(reference, image, twin);
  EXPECT_NEAR(c.mean_ratio, (3 + 1.1) / 4, 1e-6);
  EXPECT_NEAR(c.mean_relative, 0.1 / 4, 1e-6);
  EXPECT_NEAR(c.noise_mean_relative, 0.01, 1e-6);
  EXPECT_NEAR(c.worst_block, 0.1, 1e-6);
  EXPECT_NEAR(c.worst_block_ratio, 1.1, 1e-6);
  EXPECT_EQ(c.worst_block_x, 16u);
  EXPECT_EQ(c.worst_block_y, 0u);
  EXPECT_NEAR(c.worst_noise_block, 0.01, 1e-6);
  EXPECT_TRUE(c.finite);
}

// Light where the reference has none is measured against 2 % of the mean block, not against 0.
TEST(ImageComparison, ABlackReferenceBlockCountsAgainstTheMeanBlock) {
  Image reference = rgb_image(32, 16, 1.f);
  fill_block(reference, 16, 0, 0.f);  // mean block: half of a block of 1
  Image image = reference;
  fill_block(image, 16, 0, 0.005f);
  const ImageComparison c = compare_images(reference, image, image);
  EXPECT_NEAR(c.worst_block, 0.005 / (0.02 * 0.5), 1e-5);
  EXPECT_EQ(c.worst_block_x, 16u);
  EXPECT_EQ(c.worst_block_ratio, 0.0);  // undefined against black: reported as 0
  EXPECT_EQ(c.noise_mean_relative, 0.0);
}

TEST(ImageComparison, NonFiniteValuesAndMismatchedImagesAreTold) {
  const Image reference = rgb_image(16, 16, 1.f);
  Image image = reference;
  image.pixels[5] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(compare_images(reference, image, reference).finite);
  EXPECT_THROW(compare_images(reference, rgb_image(16, 8, 1.f), reference), std::invalid_argument);
  EXPECT_THROW(
      compare_images(reference, Image{16, 16, {"Y"}, std::vector<float>(256, 1.f)}, reference),
      std::invalid_argument);
}

}  // namespace
}  // namespace fb
