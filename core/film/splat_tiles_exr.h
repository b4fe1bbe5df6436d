// Splat tiles' sums (core/film/splat_tiles.h) as one UINT32 subimage of an OpenEXR file, exactly
// (each double as its two 32-bit halves, film_state_exr.h): for partial films and checkpoints.
// The tiles' pixels are stacked row by row in an image as wide as the widest tile; a table in the
// header gives each tile's index, film pixels and samples taken.
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/film/splat_tiles.h"

namespace fb {

struct SplatTilesImage {
  OIIO::ImageSpec spec;
  std::vector<uint32_t> pixels;
};

// The tiles that are there (non-null) of a film of `width` x `height` with `channels`.
SplatTilesImage encode_splat_tiles(const SplatTiles::TileList& tiles,
                                   const std::vector<std::string>& channels, uint32_t width,
                                   uint32_t height);

// Reads the current subimage of `in` into `tiles`, tile_count slots of which those the file holds
// are filled. Returns "" or what is wrong (a missing channel, a table that does not match the
// sums or the frame, a non-finite sum, a truncated file).
std::string decode_splat_tiles(OIIO::ImageInput& in, const std::vector<std::string>& channels,
                               uint32_t width, uint32_t height, size_t tile_count,
                               SplatTiles::TileList& tiles);

}  // namespace fb
