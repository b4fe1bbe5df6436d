// Splatting reconstruction, the alternative to filter importance sampling (docs/filters.md). A
// sample at film position p, drawn uniformly over its pixel, adds h(p - c_j) L and h(p - c_j) to
// every pixel j whose centre c_j lies within the filter's reach, and each pixel resolves to
// sum h L / sum h (pbrt 3e, Film::AddSample).
//
// Pixels at the film's border need the samples of pixels beyond it, so samples are drawn over a
// larger domain: the film and a margin of the filter's reach around it (as pbrt 3e's
// Film::GetSampleBounds grows by the filter radius); domain pixel (x, y) is film pixel
// (x - margin, y - margin).
//
// A sample reaches pixels of the neighbouring tiles, which other threads render at the same time.
// So each tile splats into its own buffer (the film pixels its samples can reach), and after
// rendering the buffers are added into the film pixel by pixel in tile order: every sum is formed
// in a fixed order and the image is bit-identical for any thread count (docs/conventions.md). The
// buffers hold about (1 + 2 margin / tile size)^2 times the film's own sums.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/film/film.h"
#include "core/plugin/instances.h"

namespace fb {

class SplatTiles {
 public:
  // Pixels beyond a film pixel that its samples can reach, along x (0) or y (1); also the margin
  // of the sample domain.
  uint32_t margin(int axis) const { return margin_[axis]; }
  // That margin for a filter radius: a sample at x reaches the pixels i with |i + 0.5 - x| <= r,
  // the lowest of which, for x in pixel p, is ceil(p - 0.5 - r) = p - floor(r + 0.5).
  static uint32_t reach(float radius_px) { return uint32_t(std::floor(radius_px + 0.5f)); }

  // The film pixels a tile's samples reach, clipped to the film: [x0, x1) x [y0, y1).
  struct Tile {
    uint32_t x0, y0, x1, y1;
    std::vector<double> sums;     // per pixel and channel: sum h L
    std::vector<double> weights;  // per pixel: sum h
    uint32_t samples = 0;         // the samples per pixel taken: where a resumed render goes on
    size_t index(uint32_t x, uint32_t y) const { return size_t(y - y0) * (x1 - x0) + (x - x0); }
  };
  // Per tile of the sample domain, in tile order (row by row): its buffer, or null when none of
  // its samples was taken (a part of a render takes only its own tiles').
  using TileList = std::vector<std::unique_ptr<Tile>>;

  // A film of width x height pixels, rendered in tiles of tile_size over the sample domain, into
  // `tiles`: the render's (core/film/sampling_state.h), so that a checkpoint saves them and a part
  // writes them into its partial film. Empty, it is sized here; else it holds tile_count() slots
  // (a resumed render's tiles).
  SplatTiles(uint32_t width, uint32_t height, uint32_t tile_size, size_t channels,
             const FilterInstance& filter, TileList& tiles);
  ~SplatTiles();
  // The tiles of the sample domain of such a film.
  static size_t tile_count(uint32_t width, uint32_t height, uint32_t tile_size,
                           const FilterInstance& filter);

  // The buffer of the tile whose first pixel is (x0, y0) in the sample domain; allocated by the
  // thread that renders it.
  Tile& tile(uint32_t x0, uint32_t y0);
  // Splats one sample at film position (x, y) px into `tile`. A sample with any non-finite value
  // is dropped (returns false) so that no NaN or Inf reaches the image, as in Film::add.
  bool splat(Tile& tile, float film_x, float film_y, const float* values) const;
  // Adds every tile's sums into `film`, each pixel's in tile order.
  void add_to(Film& film) const { add_splat_tiles(tiles_, film); }
  uint32_t tiles_x() const { return tiles_x_; }

  // Adds the sums of `tiles` (in tile order, as above) into `film`, each pixel's in tile order:
  // add_to, and `filmback merge` with the tiles of every part (docs/cli.md, "merge").
  static void add_splat_tiles(const TileList& tiles, Film& film);

 private:
  uint32_t width_, height_, tile_size_, tiles_x_;
  size_t channels_;
  const FilterInstance& filter_;
  float radius_[2];
  uint32_t margin_[2];  // pixels beyond a tile that its samples can reach
  TileList& tiles_;
};

}  // namespace fb
