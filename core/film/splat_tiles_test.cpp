#include "core/film/splat_tiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/plugins.h"

namespace fb {
namespace {

// The tile that renders film position (x, y): tiles are laid over the sample domain, which starts
// a margin before the film.
SplatTiles::Tile& tile_of(SplatTiles& tiles, uint32_t tile_size, float x, float y) {
  const auto origin = [&](float p, int axis) {
    return (uint32_t(std::floor(p)) + tiles.margin(axis)) / tile_size * tile_size;
  };
  return tiles.tile(origin(x, 0), origin(y, 1));
}

// Pixels reached by a sample are those whose centre lies within the radius, in whichever tile.
TEST(SplatTiles, ReachesThePixelsWithinTheRadiusAcrossTileBorders) {
  const auto filter = test::make_filter("box:radius=1.5");
  Film film(10, 6, {"R", "G", "B"});
  SplatTiles::TileList list;
  SplatTiles tiles(10, 6, 4, 3, *filter, list);
  const float v[3] = {1, 2, 3};
  // Centres i + 0.5 within 1.5 of x = 3.9: i = 2, 3 (first tile) and 4 (the next one); of
  // y = 1.0: j = 0, 1, 2 (box: the edge |d| = r counts).
  EXPECT_EQ(tiles.margin(0), 2u);  // floor(1.5 + 0.5)
  EXPECT_TRUE(tiles.splat(tile_of(tiles, 4, 3.9f, 1.0f), 3.9f, 1.0f, v));
  tiles.add_to(film);
  const Image image = film.resolve();
  for (uint32_t y = 0; y < 6; ++y)
    for (uint32_t x = 0; x < 10; ++x) {
      const bool reached = x >= 2 && x <= 4 && y <= 2;
      EXPECT_EQ(image.at(x, y, 1), reached ? 2.f : 0.f) << x << "," << y;
    }
}

TEST(SplatTiles, ResolvesToTheFilterWeightedMeanOfSamplesFromSeveralTiles) {
  const auto filter = test::make_filter("triangle:radius=2");
  Film film(8, 4, {"R", "G", "B"});
  SplatTiles::TileList list;
  SplatTiles tiles(8, 4, 4, 3, *filter, list);
  const float a[3] = {1, 1, 1}, b[3] = {5, 5, 5};
  // Domain pixels 5 and 8 (margin 2): tiles 1 and 2.
  tiles.splat(tile_of(tiles, 4, 3.2f, 1.5f), 3.2f, 1.5f, a);
  tiles.splat(tile_of(tiles, 4, 6.1f, 2.1f), 6.1f, 2.1f, b);
  tiles.add_to(film);
  const Image image = film.resolve();
  // Pixel (4, 1), centre (4.5, 1.5): weights h(3.2 - 4.5, 0) and h(6.1 - 4.5, 2.1 - 1.5).
  const double ha = filter->evaluate(3.2f - 4.5f, 0.f);
  const double hb = filter->evaluate(6.1f - 4.5f, 2.1f - 1.5f);
  EXPECT_FLOAT_EQ(image.at(4, 1, 0), float((ha * 1 + hb * 5) / (ha + hb)));
}

TEST(SplatTiles, DropsNonFiniteSamplesWhole) {
  const auto filter = test::make_filter("gaussian");
  SplatTiles::TileList list;
  SplatTiles tiles(4, 4, 4, 3, *filter, list);
  const float bad[3] = {1, std::numeric_limits<float>::infinity(), 1};
  EXPECT_FALSE(tiles.splat(tile_of(tiles, 4, 2.f, 2.f), 2.f, 2.f, bad));
  Film film(4, 4, {"R", "G", "B"});
  tiles.add_to(film);
  EXPECT_EQ(film.resolve().at(2, 2, 0), 0.f);
}

}  // namespace
}  // namespace fb
