#include "core/render/tile_partition.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fb {
namespace {

// Tiles [x0, x1) x [y0, y1).
struct TileRegion {
  uint32_t x0, y0, x1, y1;
  uint32_t extent(int axis) const { return axis == 0 ? x1 - x0 : y1 - y0; }
  uint64_t cells() const { return uint64_t(x1 - x0) * (y1 - y0); }
};

class Splitter {
 public:
  Splitter(const TileCosts& costs, bool by_area) : costs_(costs), nx_(costs.tiles_x()) {
    // A summed-area table: any rectangle's cost in four lookups.
    const uint32_t ny = costs.tiles_y();
    table_.assign(size_t(nx_ + 1) * (ny + 1), 0.0);
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx_; ++x)
        at(x + 1, y + 1) = tile_cost(x, y, by_area) + at(x, y + 1) + at(x + 1, y) - at(x, y);
  }

  void split(const TileRegion& r, uint32_t parts, std::vector<PlannedPart>& out) const {
    if (parts == 1) {
      out.push_back({pixels(r), cost(r)});
      return;
    }
    // The cut and the parts each side gets that make the larger of the two sides' best possible
    // part smallest: a side's parts cost at least its cost over their number, and at least its
    // costliest tile, which no split divides. Longer axis first, so that a tie keeps parts compact.
    const double total = cost(r);
    struct Cut {
      int axis = -1;
      uint32_t at = 0, first_parts = 0;
      double bound = INFINITY, share = INFINITY;  // share: the larger cost per part, a tie-break
    } best;
    const int longer = r.extent(0) >= r.extent(1) ? 0 : 1;
    for (int axis : {longer, 1 - longer}) {
      const uint32_t begin = axis == 0 ? r.x0 : r.y0, end = axis == 0 ? r.x1 : r.y1;
      const uint64_t line_cells = r.extent(1 - axis);
      // The costliest tile of the lines before and after each cut.
      const std::vector<double> line_max = costliest_tile_per_line(r, axis);
      std::vector<double> max_before(line_max.size() + 1, 0.0), max_after(line_max.size() + 1, 0.0);
      for (size_t i = 0; i < line_max.size(); ++i)
        max_before[i + 1] = std::max(max_before[i], line_max[i]);
      for (size_t i = line_max.size(); i-- > 0;)
        max_after[i] = std::max(max_after[i + 1], line_max[i]);
      for (uint32_t at = begin + 1; at < end; ++at) {
        const TileRegion first = side(r, axis, begin, at);
        const uint64_t first_cells = uint64_t(at - begin) * line_cells,
                       second_cells = r.cells() - first_cells;
        const double first_cost = cost(first), second_cost = total - first_cost;
        // Each side holds at least as many tiles as parts.
        const uint64_t fewest = parts > second_cells ? parts - second_cells : 1;
        const uint64_t most = std::min<uint64_t>(first_cells, parts - 1);
        if (fewest > most) continue;
        const double proportional = total > 0 ? parts * first_cost / total : parts / 2.0;
        for (double guess : {std::floor(proportional), std::ceil(proportional)}) {
          const uint32_t n1 = uint32_t(std::clamp<double>(guess, double(fewest), double(most)));
          const double share = std::max(first_cost / n1, second_cost / (parts - n1));
          const double bound = std::max({share, max_before[at - begin], max_after[at - begin]});
          if (bound < best.bound || (bound == best.bound && share < best.share))
            best = {axis, at, n1, bound, share};
        }
      }
    }
    const uint32_t begin = best.axis == 0 ? r.x0 : r.y0, end = best.axis == 0 ? r.x1 : r.y1;
    split(side(r, best.axis, begin, best.at), best.first_parts, out);
    split(side(r, best.axis, best.at, end), parts - best.first_parts, out);
  }

 private:
  double& at(uint32_t x, uint32_t y) { return table_[size_t(y) * (nx_ + 1) + x]; }
  double at(uint32_t x, uint32_t y) const { return table_[size_t(y) * (nx_ + 1) + x]; }
  double cost(const TileRegion& r) const {
    // Clamped at 0: the table's differences of large sums can round just below it.
    return std::max(0.0, at(r.x1, r.y1) - at(r.x0, r.y1) - at(r.x1, r.y0) + at(r.x0, r.y0));
  }
  double tile_cost(uint32_t x, uint32_t y, bool by_area) const {
    if (!by_area) return costs_.cost[size_t(y) * nx_ + x];
    return double(pixels({x, y, x + 1, y + 1}).area());
  }
  // Per line of `r` across `axis` (columns for x, rows for y), its costliest tile.
  std::vector<double> costliest_tile_per_line(const TileRegion& r, int axis) const {
    std::vector<double> out(r.extent(axis), 0.0);
    for (uint32_t y = r.y0; y < r.y1; ++y)
      for (uint32_t x = r.x0; x < r.x1; ++x) {
        double& m = out[axis == 0 ? x - r.x0 : y - r.y0];
        m = std::max(m, cost({x, y, x + 1, y + 1}));
      }
    return out;
  }
  static TileRegion side(const TileRegion& r, int axis, uint32_t from, uint32_t to) {
    return axis == 0 ? TileRegion{from, r.y0, to, r.y1} : TileRegion{r.x0, from, r.x1, to};
  }
  PixelRect pixels(const TileRegion& r) const {
    const uint32_t s = costs_.tile_size_px;
    return {r.x0 * s, r.y0 * s, std::min(r.x1 * s, costs_.width_px),
            std::min(r.y1 * s, costs_.height_px)};
  }

  const TileCosts& costs_;
  uint32_t nx_;
  std::vector<double> table_;
};

}  // namespace

std::vector<PlannedPart> partition_tiles(const TileCosts& costs, uint32_t parts) {
  if (costs.width_px == 0 || costs.height_px == 0 || costs.tile_size_px == 0)
    throw std::invalid_argument("partition_tiles: an empty frame");
  const uint64_t tiles = uint64_t(costs.tiles_x()) * costs.tiles_y();
  if (costs.cost.size() != tiles)
    throw std::invalid_argument("partition_tiles: " + std::to_string(costs.cost.size()) +
                                " costs for " + std::to_string(tiles) + " tiles");
  if (parts == 0 || parts > tiles)
    throw std::invalid_argument("cannot split " + std::to_string(tiles) + " tiles of " +
                                std::to_string(costs.tile_size_px) + " px into " +
                                std::to_string(parts) + " parts");
  double total = 0;
  for (double c : costs.cost) {
    if (!std::isfinite(c) || c < 0)
      throw std::invalid_argument("partition_tiles: a tile cost is negative or not finite");
    total += c;
  }
  std::vector<PlannedPart> out;
  out.reserve(parts);
  const Splitter splitter(costs, total == 0);
  splitter.split({0, 0, costs.tiles_x(), costs.tiles_y()}, parts, out);
  if (total == 0)  // split by area: the parts cost nothing
    for (PlannedPart& p : out)
      p.estimated_cost = 0;
  return out;
}

double estimated_cost(const TileCosts& costs, const PixelRect& rect) {
  const uint32_t s = costs.tile_size_px;
  double sum = 0;
  for (uint32_t ty = rect.y0 / s; ty < (rect.y1 + s - 1) / s; ++ty)
    for (uint32_t tx = rect.x0 / s; tx < (rect.x1 + s - 1) / s; ++tx)
      sum += costs.cost[size_t(ty) * costs.tiles_x() + tx];
  return sum;
}

double imbalance(const std::vector<PlannedPart>& parts) {
  double sum = 0, largest = 0;
  for (const PlannedPart& p : parts)
    sum += p.estimated_cost, largest = std::max(largest, p.estimated_cost);
  return sum > 0 ? largest * parts.size() / sum : 1.0;
}

}  // namespace fb
