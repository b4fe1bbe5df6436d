// `filmback merge PARTS... -o OUT...`: the partial films of one render's parts (core/film/
// partial_film.h) into the whole frame's film, finished and written as `filmback render` writes
// it: the same pixels, bit for bit (docs/cli.md, "Parts of a render").
#include <algorithm>
#include <iostream>

#include "core/cmd/commands.h"
#include "core/cmd/image_outputs.h"
#include "core/cmd/tile_plan_file.h"
#include "core/film/part_coverage.h"
#include "core/film/partial_film.h"
#include "core/film/splat_tiles.h"
#include "core/render/render_job.h"
#include "core/util/diagnostics.h"
#include "core/util/error.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// What differs between part `h` and the first part `first` that decides the image; empty: nothing.
std::string difference(const PartialFilmHeader& h, const PartialFilmHeader& first) {
  if (h.render_key != first.render_key)
    return "the scene file or the render's settings (spp, seed, sampler, filter, camera...)";
  if (h.width != first.width || h.height != first.height) return "the frame's size";
  if (h.reconstruction != first.reconstruction || h.splat_tile_count != first.splat_tile_count)
    return "the reconstruction";
  if (h.channels != first.channels || h.samples_per_pixel != first.samples_per_pixel)
    return "the film's channels or samples per pixel";
  const ViewSettings &a = h.view, &b = first.view;
  if (h.film_exposure != first.film_exposure || a.display_device != b.display_device ||
      a.view_transform != b.view_transform || a.look != b.look ||
      a.exposure_stops != b.exposure_stops || a.gamma != b.gamma ||
      a.dither_intensity != b.dither_intensity)
    return "the view settings or exposure";
  return "";
}

// Every part of the same render, and together the frame, or an InputError naming the file.
void check_parts(const std::vector<fs::path>& files, const std::vector<PartialFilmHeader>& parts) {
  for (size_t i = 1; i < parts.size(); ++i)
    if (const std::string what = difference(parts[i], parts[0]); !what.empty())
      throw_input(files[i].string(), "",
                  "a part of another render than '" + files[0].string() + "' (" + what +
                      " differ); nothing written");
  std::vector<PixelRect> crops;
  for (const PartialFilmHeader& p : parts)
    crops.push_back(p.crop);
  const std::optional<CoverageProblem> problem =
      check_coverage(crops, parts[0].width, parts[0].height);
  if (!problem) return;
  if (problem->kind == CoverageProblem::Kind::kGap)
    throw InputError("filmback merge: no part covers pixels " + problem->where.text() +
                     " of the " + std::to_string(parts[0].width) + "x" +
                     std::to_string(parts[0].height) + " frame (a missing part?); nothing written");
  throw_input(files[problem->part].string(), "",
              "its crop " + crops[problem->part].text() + " overlaps the crop " +
                  crops[problem->other].text() + " of '" + files[problem->other].string() +
                  "' (at pixels " + problem->where.text() + "); nothing written");
}

// The whole render's metadata: the first part's, with the parts' render seconds and dropped
// samples summed.
ImageMetadata merged_metadata(const std::vector<PartialFilmHeader>& parts) {
  ImageMetadata m = parts[0].metadata;
  double seconds = 0;
  uint64_t dropped = 0;
  for (const PartialFilmHeader& p : parts)
    seconds += p.render_seconds, dropped += p.dropped_samples;
  for (auto& [name, value] : m.floats)
    if (name == "filmback/render_seconds") value = float(seconds);
  for (auto& [name, value] : m.ints)
    if (name == "filmback/dropped_samples") value = int(std::min<uint64_t>(dropped, INT32_MAX));
  return m;
}

}  // namespace

int run_merge(const MergeCommand& command) {
  check_outputs(command.outputs);
  if (command.parts.size() > kMaxParts)
    throw UsageError("merge: " + std::to_string(command.parts.size()) +
                     " parts, expected at most " + std::to_string(kMaxParts));
  std::vector<PartialFilmHeader> parts;
  for (const fs::path& file : command.parts)
    parts.push_back(read_partial_film_header(file));
  check_parts(command.parts, parts);
  const PartialFilmHeader& first = parts[0];
  Diagnostics diagnostics;
  const OutputView view = output_view(first.view, {command.parts[0].string(), ""},
                                      command.outputs, command.ocio_config, diagnostics);
  diagnostics.print(std::cerr);

  Film film(first.width, first.height, first.channels);
  SplatTiles::TileList splat_tiles(first.splat_tile_count);
  for (size_t i = 0; i < parts.size(); ++i)
    read_partial_film(command.parts[i], parts[i], film, splat_tiles);
  if (first.reconstruction == Reconstruction::kSplat) {
    // The sums are the tiles', added in the whole frame's tile order into an empty film, as a
    // whole render adds them (SplatTiles::add_to); the crops' own sums only held their parts'.
    for (size_t tile = 0; tile < splat_tiles.size(); ++tile)
      if (!splat_tiles[tile])
        throw InputError("filmback merge: no part holds splat tile " + std::to_string(tile) +
                         " (a part truncated or written by another version?); nothing written");
    std::fill_n(film.sums(), film.pixel_count() * film.channels().size(), 0.0);
    std::fill_n(film.weights(), film.pixel_count(), 0.0);
    SplatTiles::add_splat_tiles(splat_tiles, film);
    film.set_sample_count(0, 0, film.width(), film.height(), first.samples_per_pixel);
  }
  Image image = film.resolve();
  apply_film_exposure(image, first.film_exposure);
  write_outputs(image, merged_metadata(parts), view, command.outputs);
  std::cout << "filmback: merged " << parts.size() << " parts into " << first.width << "x"
            << first.height << std::endl;
  return 0;
}

}  // namespace fb
