#include "core/render/tile_partition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <stdexcept>

namespace fb {
namespace {

TileCosts uniform_costs(uint32_t width, uint32_t height, double each = 1.0) {
  TileCosts c{width, height, 16, {}};
  c.cost.assign(size_t(c.tiles_x()) * c.tiles_y(), each);
  return c;
}

// Every pixel of the frame in exactly one part, each part inside the frame and holding a tile.
void expect_exact_cover(const TileCosts& costs, const std::vector<PlannedPart>& parts) {
  std::vector<int> owner(size_t(costs.width_px) * costs.height_px, 0);
  for (const PlannedPart& p : parts) {
    ASSERT_LT(p.crop.x0, p.crop.x1);
    ASSERT_LT(p.crop.y0, p.crop.y1);
    ASSERT_LE(p.crop.x1, costs.width_px);
    ASSERT_LE(p.crop.y1, costs.height_px);
    EXPECT_EQ(p.crop.x0 % costs.tile_size_px, 0u);
    EXPECT_EQ(p.crop.y0 % costs.tile_size_px, 0u);
    for (uint32_t y = p.crop.y0; y < p.crop.y1; ++y)
      for (uint32_t x = p.crop.x0; x < p.crop.x1; ++x)
        ++owner[size_t(y) * costs.width_px + x];
  }
  for (int o : owner)
    ASSERT_EQ(o, 1);
}

TEST(TilePartition, CoversTheFrameExactlyForManySizesAndCounts) {
  std::mt19937 rng(7);
  for (uint32_t width : {16u, 17u, 100u, 480u})
    for (uint32_t height : {1u, 16u, 33u, 270u}) {
      TileCosts costs = uniform_costs(width, height);
      std::uniform_real_distribution<double> u(0.0, 3.0);
      for (double& c : costs.cost)
        c = u(rng);
      const uint32_t tiles = costs.tiles_x() * costs.tiles_y();
      for (uint32_t n : {1u, 2u, 3u, 7u, 8u, 64u, tiles})
        if (n <= tiles) {
          const auto parts = partition_tiles(costs, n);
          ASSERT_EQ(parts.size(), n);
          expect_exact_cover(costs, parts);
        }
    }
}

TEST(TilePartition, AsManyPartsAsTilesGivesOneTileEach) {
  const TileCosts costs = uniform_costs(48, 48);  // 3 x 3 tiles: no even split exists at 9
  const auto parts = partition_tiles(costs, 9);
  expect_exact_cover(costs, parts);
  for (const PlannedPart& p : parts)
    EXPECT_EQ(p.crop.area(), 256u);
}

TEST(TilePartition, UniformCostsGiveEqualParts) {
  const auto parts = partition_tiles(uniform_costs(256, 128), 8);  // 16 x 8 tiles
  for (const PlannedPart& p : parts)
    EXPECT_DOUBLE_EQ(p.estimated_cost, 16.0);
  EXPECT_DOUBLE_EQ(imbalance(parts), 1.0);
}

TEST(TilePartition, AHotTileGetsTheSmallestPart) {
  TileCosts costs = uniform_costs(256, 256);  // 16 x 16 tiles of cost 1
  costs.cost[5 * 16 + 9] = 60;                // one tile costs a fifth of the frame
  const auto parts = partition_tiles(costs, 8);
  expect_exact_cover(costs, parts);
  uint64_t hot_area = 0, smallest_other = UINT64_MAX;
  for (const PlannedPart& p : parts)
    if (p.crop.x0 <= 9 * 16 && 9 * 16 < p.crop.x1 && p.crop.y0 <= 5 * 16 && 5 * 16 < p.crop.y1)
      hot_area = p.crop.area();
    else
      smallest_other = std::min(smallest_other, p.crop.area());
  EXPECT_LT(hot_area, smallest_other);
  // No split beats the hot tile alone (60, against a mean of 315 / 8); a greedy split of
  // rectangles gets within 15 % of it.
  const double best_possible = 60 / (315.0 / 8);
  EXPECT_GE(imbalance(parts), best_possible - 1e-9);
  EXPECT_LE(imbalance(parts), 1.15 * best_possible);
}

TEST(TilePartition, CostlierHalfGetsMoreParts) {
  TileCosts costs = uniform_costs(512, 64);  // 32 x 4 tiles; the left half costs 3 x the right
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 16; ++x)
      costs.cost[y * 32 + x] = 3;
  const auto parts = partition_tiles(costs, 8);
  expect_exact_cover(costs, parts);
  // Parts of 10.67 tiles of cost 3 cannot be rectangles; 12 tiles (36 against 32) can.
  EXPECT_LE(imbalance(parts), 36.0 / 32 + 1e-9);
  int left = 0;
  for (const PlannedPart& p : parts)
    left += p.crop.x1 <= 256;
  EXPECT_EQ(left, 6);
}

TEST(TilePartition, ZeroCostsSplitByArea) {
  const TileCosts even = uniform_costs(96, 48, 0.0);  // 6 x 3 tiles
  for (const PlannedPart& p : partition_tiles(even, 3)) {
    EXPECT_EQ(p.crop.area(), 96u * 48 / 3);
    EXPECT_EQ(p.estimated_cost, 0.0);
  }
  // 7 x 3 tiles, the last column 4 px wide and the last row 8 px tall: no part is more than a
  // column of tiles (16 x 40 px) above the mean.
  const TileCosts ragged = uniform_costs(100, 40, 0.0);
  const auto parts = partition_tiles(ragged, 3);
  expect_exact_cover(ragged, parts);
  for (const PlannedPart& p : parts)
    EXPECT_LE(double(p.crop.area()), 4000.0 / 3 + 16 * 40);
}

TEST(TilePartition, RefusesImpossibleRequests) {
  const TileCosts costs = uniform_costs(32, 32);
  EXPECT_THROW(partition_tiles(costs, 0), std::invalid_argument);
  EXPECT_THROW(partition_tiles(costs, 5), std::invalid_argument);
  TileCosts bad = costs;
  bad.cost[2] = -1;
  EXPECT_THROW(partition_tiles(bad, 2), std::invalid_argument);
  bad.cost[2] = NAN;
  EXPECT_THROW(partition_tiles(bad, 2), std::invalid_argument);
  bad.cost.pop_back();
  EXPECT_THROW(partition_tiles(bad, 2), std::invalid_argument);
}

}  // namespace
}  // namespace fb
