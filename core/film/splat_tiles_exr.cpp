#include "core/film/splat_tiles_exr.h"

#include <algorithm>
#include <sstream>

#include "core/film/film_state_exr.h"

namespace fb {
namespace {

constexpr const char* kSplatTileTable = "filmback/splat_tile_table";

}  // namespace

SplatTilesImage encode_splat_tiles(const SplatTiles::TileList& tiles,
                                   const std::vector<std::string>& channels, uint32_t width,
                                   uint32_t height) {
  uint32_t image_width = 1, rows = 0;
  for (const std::unique_ptr<SplatTiles::Tile>& t : tiles)
    if (t) image_width = std::max(image_width, t->x1 - t->x0), rows += t->y1 - t->y0;
  rows = std::max(rows, 1u);
  const size_t n = channels.size(), stride = 2 * n + 2;
  SplatTilesImage image{
      OIIO::ImageSpec(int(image_width), int(rows), int(stride), OIIO::TypeDesc::UINT32),
      std::vector<uint32_t>(size_t(image_width) * rows * stride, 0)};
  image.spec.channelnames = film_state_channels(channels, false);
  // OpenEXR's parts of one file share the display window.
  image.spec.full_width = int(width), image.spec.full_height = int(height);
  image.spec.attribute("compression", "zip");
  std::string table;
  uint32_t row = 0;
  for (size_t index = 0; index < tiles.size(); ++index) {
    const SplatTiles::Tile* t = tiles[index].get();
    if (!t) continue;
    table += std::to_string(index) + " " + std::to_string(t->x0) + " " + std::to_string(t->y0) +
             " " + std::to_string(t->x1) + " " + std::to_string(t->y1) + " " +
             std::to_string(t->samples) + "\n";
    for (uint32_t y = t->y0; y < t->y1; ++y, ++row)
      for (uint32_t x = t->x0; x < t->x1; ++x) {
        const size_t p = t->index(x, y);
        pack_sums(&t->sums[p * n], t->weights[p], n,
                  &image.pixels[(size_t(row) * image_width + (x - t->x0)) * stride]);
      }
  }
  image.spec.attribute(kSplatTileTable, table);
  return image;
}

std::string decode_splat_tiles(OIIO::ImageInput& in, const std::vector<std::string>& channels,
                               uint32_t width, uint32_t height, size_t tile_count,
                               SplatTiles::TileList& tiles) {
  const OIIO::ImageSpec& spec = in.spec();
  const size_t n = channels.size();
  std::vector<int> index;
  if (std::string why = channel_positions(spec, film_state_channels(channels, false), index);
      !why.empty())
    return why;
  const size_t stride = size_t(spec.nchannels);
  std::vector<uint32_t> pixels(size_t(spec.width) * spec.height * stride);
  if (!in.read_image(in.current_subimage(), 0, 0, spec.nchannels, OIIO::TypeDesc::UINT32,
                     pixels.data()))
    return in.geterror();
  tiles.clear();
  tiles.resize(tile_count);
  std::istringstream table(spec.get_string_attribute(kSplatTileTable));
  uint32_t row = 0;
  for (size_t tile; table >> tile;) {
    auto t = std::make_unique<SplatTiles::Tile>();
    if (!(table >> t->x0 >> t->y0 >> t->x1 >> t->y1 >> t->samples) || tile >= tile_count ||
        tiles[tile] || t->x1 <= t->x0 || t->y1 <= t->y0 || t->x1 > width || t->y1 > height ||
        t->x1 - t->x0 > uint32_t(spec.width) || row + (t->y1 - t->y0) > uint32_t(spec.height))
      return "its splat tile table does not match its tiles' sums";
    const size_t pixel_count = size_t(t->x1 - t->x0) * (t->y1 - t->y0);
    t->sums.resize(pixel_count * n), t->weights.resize(pixel_count);
    for (uint32_t y = t->y0; y < t->y1; ++y, ++row)
      for (uint32_t x = t->x0; x < t->x1; ++x) {
        const size_t p = t->index(x, y);
        if (!unpack_sums(&pixels[(size_t(row) * spec.width + (x - t->x0)) * stride], index, n,
                         &t->sums[p * n], t->weights[p]))
          return "splat tile " + std::to_string(tile) + " holds a non-finite sum";
      }
    tiles[tile] = std::move(t);
  }
  return "";
}

}  // namespace fb
