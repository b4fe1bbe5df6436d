// A partial film: one part of a render (`filmback render --tile I/N` or `--crop`), the film's raw
// state over the part's crop, so that `filmback merge` can form the whole frame's film exactly and
// finish it as `filmback render` would (docs/cli.md, "Parts of a render").
//
// The file is an OpenEXR image. Subimage 0 is the film state over the crop (film_state_exr.h: each
// double as two UINT32 halves, exactly as checkpoints store it): its data window is the crop, its
// display window the whole frame. Its header holds the render key (everything that decides the
// samples: parts of different renders are refused), the finishing information (film exposure,
// view settings, the image metadata a whole render writes) and the seconds each 16x16 tile of
// the crop took. With splatting, subimage 1 holds the part's splat tiles' sums and samples
// (splat_tiles_exr.h: the film pixels their samples reach, inside the crop or not), so that merge
// adds every tile's sums in the whole frame's tile order, as SplatTiles::add_to does: pixel sums
// formed in the same order, the same bits. With adaptive sampling the part sampled an apron
// around its crop (render_loop.h, part_region); the file holds the crop's pixels only.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/film/film.h"
#include "core/film/pixel_rect.h"
#include "core/film/splat_tiles.h"
#include "core/image/image_io.h"
#include "core/image/view_settings.h"

namespace fb {

struct PartialFilmHeader {
  uint32_t width = 0, height = 0;  // the whole frame, pixels
  PixelRect crop;                  // this part
  std::string render_key;          // the same key a checkpoint of the whole render carries
  Reconstruction reconstruction = Reconstruction::kImportance;
  std::vector<std::string> channels;  // the film's
  uint32_t samples_per_pixel = 0;
  // Splatting: the sample domain's tiles (SplatTiles::tile_count), every part's together.
  uint64_t splat_tile_count = 0;
  // What finishing the film takes: the film exposure gain (Cycles' Film > Exposure), the view
  // settings of 8-bit outputs and the metadata the whole render's images carry (its render
  // seconds and dropped samples this part's).
  double film_exposure = 1;
  ViewSettings view;
  ImageMetadata metadata;
  double render_seconds = 0;
  uint64_t dropped_samples = 0;
  // The seconds each 16x16 film tile of the crop took, row by row over the tiles
  // [tiles.x0, tiles.x1) x [tiles.y0, tiles.y1) (in tiles), for cost-balanced plans.
  PixelRect tiles;
  std::vector<double> tile_seconds;
};

// Writes the part (the film over header.crop; with splatting the tiles' buffers too) through a
// temporary file and a rename. Throws InputError naming the file.
void write_partial_film(const std::filesystem::path& file, const PartialFilmHeader& header,
                        const Film& film, const SplatTiles::TileList& splat_tiles);

// The header alone. Throws InputError naming the file when it cannot be read or is not a filmback
// partial film of this version (or its header is inconsistent: a crop outside the frame...).
PartialFilmHeader read_partial_film_header(const std::filesystem::path& file);

// The part's film state into `film` (the whole frame's size and channels) over header.crop, and
// with splatting its tiles into `splat_tiles` (sized splat_tile_count; a tile
// already there, another part's, is an error: the parts overlap). Throws InputError naming the
// file when the data is truncated or corrupt.
void read_partial_film(const std::filesystem::path& file, const PartialFilmHeader& header,
                       Film& film, SplatTiles::TileList& splat_tiles);

// The whole frame's film from every part of one render (`files[i]` read into `headers[i]`):
// refuses (InputError naming the file) parts of another render (key, size, settings), parts that
// overlap, a frame they leave uncovered (naming the pixels), truncated or corrupt data. With
// splatting, the tiles' sums are added in the whole frame's tile order into an empty film, as
// SplatTiles::add_to does in a whole render.
Film merge_partial_films(const std::vector<std::filesystem::path>& files,
                         const std::vector<PartialFilmHeader>& headers);

}  // namespace fb
