#include "core/film/checkpoint.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "core/film/convergence_exr.h"
#include "core/film/film_state_exr.h"
#include "core/film/splat_tiles_exr.h"
#include "core/util/error.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// 2: the sampling state's subimages (version 1 held the film alone).
constexpr int kCheckpointVersion = 2;
constexpr const char* kContent = "filmback/checkpoint_content";
constexpr const char* kSplatTilesContent = "splat_tiles";
constexpr const char* kConvergenceContent = "convergence";

[[noreturn]] void fail(const fs::path& file, const std::string& why) {
  throw InputError(located(file.string(), "", "cannot resume from this checkpoint: " + why));
}

// Every pixel's count at most the target; within a 16-pixel tile of the film, the pixels still
// sampled (all of them without adaptive sampling) at the count of the first of them, the
// converged ones at most that. Splatting's tiles lie on the sample domain, not the film's grid:
// their counts are checked per splat tile.
void check_counts(const fs::path& file, const Film& film, const SamplingState& state,
                  const PixelRect& saved, uint32_t samples_per_pixel, uint32_t tile_size) {
  const bool splat = !state.splat_tiles.empty();
  const ConvergenceMap* convergence = state.convergence ? &*state.convergence : nullptr;
  const auto converged = [&](uint32_t x, uint32_t y) {
    return convergence && convergence->converged(x, y);
  };
  for (uint32_t ty = saved.y0 - saved.y0 % tile_size; ty < saved.y1; ty += tile_size)
    for (uint32_t tx = saved.x0 - saved.x0 % tile_size; tx < saved.x1; tx += tile_size) {
      const PixelRect tile{std::max(tx, saved.x0), std::max(ty, saved.y0),
                           std::min(tx + tile_size, saved.x1), std::min(ty + tile_size, saved.y1)};
      // The first pixel still sampled gives the tile's count; none left: the target bounds all.
      std::optional<uint32_t> tile_count;
      for (uint32_t y = tile.y0; y < tile.y1 && !tile_count && !splat; ++y)
        for (uint32_t x = tile.x0; x < tile.x1 && !tile_count; ++x)
          if (!converged(x, y)) tile_count = film.sample_count(x, y);
      for (uint32_t y = tile.y0; y < tile.y1; ++y)
        for (uint32_t x = tile.x0; x < tile.x1; ++x) {
          const uint32_t count = film.sample_count(x, y);
          const bool possible = !tile_count       ? count <= samples_per_pixel
                                : converged(x, y) ? count <= *tile_count
                                                  : count == *tile_count;
          if (!possible || count > samples_per_pixel)
            fail(file, "pixel " + std::to_string(x) + "," + std::to_string(y) + " has " +
                           std::to_string(count) + " samples, which a render of " +
                           std::to_string(samples_per_pixel) + " per pixel cannot have left");
        }
    }
  for (size_t tile = 0; tile < state.splat_tiles.size(); ++tile)
    if (const SplatTiles::Tile* t = state.splat_tiles[tile].get();
        t && t->samples > samples_per_pixel)
      fail(file, "splat tile " + std::to_string(tile) + " has " + std::to_string(t->samples) +
                     " samples, which a render of " + std::to_string(samples_per_pixel) +
                     " per pixel cannot have left");
}

}  // namespace

void write_checkpoint(const Film& film, const SamplingState& state, const std::string& key,
                      const fs::path& file, const std::optional<PixelRect>& region) {
  const PixelRect saved = region.value_or(whole_frame(film.width(), film.height()));
  const std::vector<uint32_t> pixels = encode_film_state(film, saved);
  std::vector<StateImage> images{{film_state_spec(film, saved), pixels.data()}};
  images[0].spec.attribute("filmback/checkpoint_version", kCheckpointVersion);
  images[0].spec.attribute("filmback/checkpoint_key", key);
  SplatTilesImage splat_tiles;
  if (!state.splat_tiles.empty()) {
    splat_tiles =
        encode_splat_tiles(state.splat_tiles, film.channels(), film.width(), film.height());
    splat_tiles.spec.attribute(kContent, kSplatTilesContent);
    images.push_back({splat_tiles.spec, splat_tiles.pixels.data()});
  }
  std::vector<uint32_t> convergence;
  if (state.convergence) {
    convergence = encode_convergence(*state.convergence, saved);
    images.push_back({convergence_spec(*state.convergence, saved), convergence.data()});
    images.back().spec.attribute(kContent, kConvergenceContent);
  }
  write_state_images(file, images);
}

void read_checkpoint(const fs::path& file, const std::string& key, uint32_t samples_per_pixel,
                     uint32_t tile_size, Film& film, SamplingState& state,
                     const std::optional<PixelRect>& region) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) fail(file, OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const int version = spec.get_int_attribute("filmback/checkpoint_version");
  if (version > 0 && version != kCheckpointVersion)
    fail(file, "it is a version " + std::to_string(version) + " checkpoint, this filmback reads " +
                   std::to_string(kCheckpointVersion) +
                   " (an earlier filmback wrote it): render again without --resume");
  if (version != kCheckpointVersion)
    fail(file,
         "it is not a filmback checkpoint (version " + std::to_string(kCheckpointVersion) + ")");
  if (spec.get_string_attribute("filmback/checkpoint_key") != key)
    fail(file,
         "it was written for another render (the scene file or the render's settings "
         "differ: the same scene, options, seed and part are needed)");
  const PixelRect saved = region.value_or(whole_frame(film.width(), film.height()));
  if (const std::string why = decode_film_state(*in, saved, film); !why.empty()) fail(file, why);
  // The sampling state's subimages, each where its content says.
  const size_t splat_tile_count = state.splat_tiles.size();
  bool splat_found = false, convergence_found = false;
  for (int subimage = 1; in->seek_subimage(subimage, 0); ++subimage) {
    const std::string content = in->spec().get_string_attribute(kContent);
    std::string why;
    if (content == kSplatTilesContent && splat_tile_count > 0) {
      why = decode_splat_tiles(*in, film.channels(), film.width(), film.height(), splat_tile_count,
                               state.splat_tiles);
      splat_found = true;
    } else if (content == kConvergenceContent && state.convergence) {
      why = decode_convergence(*in, saved, *state.convergence);
      convergence_found = true;
    } else {
      why = "subimage " + std::to_string(subimage) + " holds '" + content +
            "', which this render does not keep";
    }
    if (!why.empty()) fail(file, why);
  }
  if (splat_tile_count > 0 && !splat_found) fail(file, "its splat tiles are missing");
  if (state.convergence && !convergence_found) fail(file, "its convergence map is missing");
  check_counts(file, film, state, saved, samples_per_pixel, tile_size);
  if (splat_tile_count > 0)
    for (uint32_t y = saved.y0; y < saved.y1; ++y) {
      const size_t row = size_t(y) * film.width();
      std::fill(film.sums() + (row + saved.x0) * film.channels().size(),
                film.sums() + (row + saved.x1) * film.channels().size(), 0.0);
      std::fill(film.weights() + row + saved.x0, film.weights() + row + saved.x1, 0.0);
    }
}

}  // namespace fb
