#include "tests/blender/blobs.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace fb::test {
namespace {

Image black_rgb(uint32_t width, uint32_t height) {
  return {width, height, {"B", "G", "R"}, std::vector<float>(size_t(width) * height * 3, 0.f)};
}

void set_red(Image& image, uint32_t x, uint32_t y, float value) {
  image.pixels[(size_t(y) * image.width + x) * 3 + 2] = value;  // channel 2 is R: found by name
}

TEST(Blobs, DiagonalNeighboursJoinAndTheCentroidIsFluxWeightedAtPixelCentres) {
  Image image = black_rgb(8, 6);
  set_red(image, 1, 1, 1.f);
  set_red(image, 2, 2, 3.f);  // touches (1, 1) only at a corner
  set_red(image, 6, 4, 2.f);  // a second blob
  const std::vector<Blob> blobs = find_blobs(image, 0.0);
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_EQ(blobs[0].pixel_count, 2u);
  EXPECT_DOUBLE_EQ(blobs[0].flux, 4.0);
  EXPECT_DOUBLE_EQ(blobs[0].x_px, (1.0 * 1.5 + 3.0 * 2.5) / 4.0);
  EXPECT_DOUBLE_EQ(blobs[0].y_px, (1.0 * 1.5 + 3.0 * 2.5) / 4.0);
  EXPECT_DOUBLE_EQ(blobs[1].x_px, 6.5);
  EXPECT_DOUBLE_EQ(blobs[1].y_px, 4.5);
}

TEST(Blobs, PixelsAtOrBelowTheThresholdAreBackground) {
  Image image = black_rgb(4, 1);
  set_red(image, 0, 0, 0.5f);
  set_red(image, 1, 0, 0.25f);
  set_red(image, 2, 0, 0.5f);
  EXPECT_EQ(find_blobs(image, 0.25).size(), 2u);
  EXPECT_EQ(find_blobs(image, 0.2).size(), 1u);
}

TEST(Blobs, MissingColourChannelIsAnError) {
  Image image{2, 2, {"Y"}, std::vector<float>(4, 1.f)};
  EXPECT_THROW(find_blobs(image, 0.0), std::runtime_error);
}

}  // namespace
}  // namespace fb::test
