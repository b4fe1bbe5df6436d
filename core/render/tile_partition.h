// Splitting a frame into parts of near-equal cost, for renders spread over several processes or
// machines (docs/distributed.md): one heavy corner of a frame must not hold the whole frame.
//
// The parts are rectangles of whole render tiles (kTileSize pixels; the last row and column may
// be narrower), found by a recursive split like a k-d tree's: a region meant for n parts is cut
// along a tile line into two regions meant for floor(n/2) and ceil(n/2) parts, at the line whose
// cost comes nearest those shares. Rectangles keep the merge's checks simple (disjoint, covering
// the frame) and a part's pixels together in memory and in the scene.
#pragma once

#include <cstdint>
#include <vector>

#include "core/film/pixel_rect.h"

namespace fb {

// A frame's estimated cost per render tile, rows of tiles top first (any unit: seconds, rays).
struct TileCosts {
  uint32_t width_px = 0, height_px = 0, tile_size_px = 0;
  std::vector<double> cost;  // tiles_x() * tiles_y() values, each finite and >= 0

  uint32_t tiles_x() const { return (width_px + tile_size_px - 1) / tile_size_px; }
  uint32_t tiles_y() const { return (height_px + tile_size_px - 1) / tile_size_px; }
};

struct PlannedPart {
  PixelRect crop;
  double estimated_cost = 0;  // the sum of its tiles' costs
};

// `parts` rectangles covering the frame, disjoint, each holding at least one tile, ordered as
// the split made them (top-left first). Costs that are all zero split the frame by area. Throws
// std::invalid_argument when `parts` is 0 or exceeds the tile count, or a cost is negative or
// not finite.
std::vector<PlannedPart> partition_tiles(const TileCosts& costs, uint32_t parts);

// The sum of the costs of the tiles `rect` covers (whole tiles: `rect` starts on tile lines).
double estimated_cost(const TileCosts& costs, const PixelRect& rect);

// The largest part's cost over the mean part's: 1 is a perfect balance, and the makespan of the
// parts run side by side is this times the ideal.
double imbalance(const std::vector<PlannedPart>& parts);

}  // namespace fb
