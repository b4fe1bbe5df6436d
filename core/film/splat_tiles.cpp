#include "core/film/splat_tiles.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace fb {

SplatTiles::SplatTiles(uint32_t width, uint32_t height, uint32_t tile_size, size_t channels,
                       const FilterInstance& filter, TileList& tiles)
    : width_(width),
      height_(height),
      tile_size_(tile_size),
      channels_(channels),
      filter_(filter),
      tiles_(tiles) {
  filter.radius(radius_);
  for (int axis = 0; axis < 2; ++axis)
    margin_[axis] = reach(radius_[axis]);
  tiles_x_ = (width + 2 * margin_[0] + tile_size - 1) / tile_size;
  if (tiles_.empty()) tiles_.resize(tile_count(width, height, tile_size, filter));
}

size_t SplatTiles::tile_count(uint32_t width, uint32_t height, uint32_t tile_size,
                              const FilterInstance& filter) {
  float radius[2];
  filter.radius(radius);
  const auto tiles = [&](uint32_t side, float r) {
    return (side + 2 * reach(r) + tile_size - 1) / tile_size;
  };
  return size_t(tiles(width, radius[0])) * tiles(height, radius[1]);
}

SplatTiles::~SplatTiles() = default;

SplatTiles::Tile& SplatTiles::tile(uint32_t x0, uint32_t y0) {
  std::unique_ptr<Tile>& slot = tiles_[size_t(y0 / tile_size_) * tiles_x_ + x0 / tile_size_];
  if (!slot) {
    // Its samples lie in film pixels [x0 - margin, x0 + tile - margin) and reach a margin further.
    auto t = std::make_unique<Tile>();
    t->x0 = x0 > 2 * margin_[0] ? x0 - 2 * margin_[0] : 0;
    t->y0 = y0 > 2 * margin_[1] ? y0 - 2 * margin_[1] : 0;
    t->x1 = std::min<uint64_t>(width_, uint64_t(x0) + tile_size_);
    t->y1 = std::min<uint64_t>(height_, uint64_t(y0) + tile_size_);
    const size_t pixels = size_t(t->x1 - t->x0) * (t->y1 - t->y0);
    t->sums.assign(pixels * channels_, 0.0);
    t->weights.assign(pixels, 0.0);
    slot = std::move(t);
  }
  return *slot;
}

bool SplatTiles::splat(Tile& tile, float film_x, float film_y, const float* values) const {
  for (size_t c = 0; c < channels_; ++c)
    if (!std::isfinite(values[c])) return false;
  // Pixel centres i + 0.5 within the radius of the sample, clipped to the tile's buffer.
  const auto first = [](float p, float r, uint32_t lo) {
    return uint32_t(std::max<double>(lo, std::ceil(double(p) - 0.5 - r)));
  };
  const auto last = [](float p, float r, uint32_t hi) {  // exclusive
    return uint32_t(std::clamp<double>(std::floor(double(p) - 0.5 + r) + 1, 0, hi));
  };
  const uint32_t i0 = first(film_x, radius_[0], tile.x0), i1 = last(film_x, radius_[0], tile.x1);
  const uint32_t j0 = first(film_y, radius_[1], tile.y0), j1 = last(film_y, radius_[1], tile.y1);
  for (uint32_t j = j0; j < j1; ++j)
    for (uint32_t i = i0; i < i1; ++i) {
      // h(x - x_j): the sample's offset from the pixel centre, as in importance sampling.
      const float h = filter_.evaluate(film_x - (float(i) + 0.5f), film_y - (float(j) + 0.5f));
      if (h == 0.f) continue;
      const size_t pixel = tile.index(i, j);
      double* sum = &tile.sums[pixel * channels_];
      for (size_t c = 0; c < channels_; ++c)
        sum[c] += double(h) * values[c];
      tile.weights[pixel] += h;
    }
  return true;
}

void SplatTiles::add_splat_tiles(const TileList& tiles, Film& film) {
  const size_t channels = film.channels().size();
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, film.height()), [&](const auto& rows) {
    for (uint32_t y = rows.begin(); y != rows.end(); ++y)
      for (const std::unique_ptr<Tile>& t : tiles) {  // in tile order
        if (!t || y < t->y0 || y >= t->y1) continue;
        for (uint32_t x = t->x0; x < t->x1; ++x) {
          const size_t pixel = t->index(x, y);
          film.add_sums(x, y, &t->sums[pixel * channels], t->weights[pixel]);
        }
      }
  });
}

}  // namespace fb
