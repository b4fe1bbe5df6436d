#include "core/film/partial_film.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <sstream>

#include "core/film/film_state_exr.h"
#include "core/film/part_coverage.h"
#include "core/film/splat_tiles_exr.h"
#include "core/util/error.h"
#include "core/util/parse_number.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// 2: the splat tiles' table gives each tile's samples (splat_tiles_exr.h); parts of adaptive
// renders (their apron, render_loop.h).
constexpr int kPartialFilmVersion = 2;
constexpr const char* kPrefix = "filmback/part/";
// Metadata entries: kMetadata + a 4-digit position (OpenEXR sorts attributes by name) + a type
// letter (f float, i int, s string, m matrix) + ":" + the entry's name.
constexpr const char* kMetadata = "filmback/part/metadata/";
constexpr uint32_t kTile = 16;  // the film tiles whose seconds are recorded (render_loop.h)

std::string attr(const char* name) {
  return std::string(kPrefix) + name;
}

// Doubles as text that reads back to the same bits.
std::string exact_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

[[noreturn]] void fail(const fs::path& file, const std::string& where, const std::string& why) {
  throw InputError(located(file.string(), where, why));
}

double exact_number(const fs::path& file, const OIIO::ImageSpec& spec, const char* name) {
  const std::optional<double> v = parse_number(spec.get_string_attribute(attr(name)));
  if (!v) fail(file, attr(name), "expected a number");
  return *v;
}

void put_metadata(const ImageMetadata& m, OIIO::ImageSpec& spec) {
  int position = 0;
  const auto name = [&](char type, const std::string& entry) {
    char number[8];
    std::snprintf(number, sizeof number, "%04d", position++);
    return std::string(kMetadata) + number + type + ":" + entry;
  };
  for (const auto& [key, value] : m.matrices)
    spec.attribute(name('m', key), OIIO::TypeDesc::TypeMatrix44, value.data());
  for (const auto& [key, value] : m.floats)
    spec.attribute(name('f', key), value);
  for (const auto& [key, value] : m.ints)
    spec.attribute(name('i', key), value);
  for (const auto& [key, value] : m.strings)
    spec.attribute(name('s', key), value);
}

ImageMetadata get_metadata(const OIIO::ImageSpec& spec) {
  std::vector<const OIIO::ParamValue*> entries;
  const std::string prefix = kMetadata;
  for (const OIIO::ParamValue& p : spec.extra_attribs)
    if (p.name().string().rfind(prefix, 0) == 0 && p.name().size() > prefix.size() + 6)
      entries.push_back(&p);
  std::sort(entries.begin(), entries.end(),
            [](auto* a, auto* b) { return a->name().string() < b->name().string(); });
  ImageMetadata m;
  for (const OIIO::ParamValue* p : entries) {
    const std::string full = p->name().string();
    const char type = full[prefix.size() + 4];
    const std::string key = full.substr(prefix.size() + 6);
    if (type == 'm' && p->type() == OIIO::TypeDesc::TypeMatrix44) {
      ImageMetadata::Matrix matrix;
      std::copy_n(static_cast<const float*>(p->data()), 16, matrix.begin());
      m.matrices.push_back({key, matrix});
    } else if (type == 'f' && p->type() == OIIO::TypeDesc::TypeFloat) {
      m.floats.push_back({key, p->get_float()});
    } else if (type == 'i' && p->type() == OIIO::TypeDesc::TypeInt) {
      m.ints.push_back({key, p->get_int()});
    } else if (type == 's' && p->type() == OIIO::TypeDesc::TypeString) {
      m.strings.push_back({key, p->get_string()});
    }
  }
  return m;
}

std::string joined(const std::vector<double>& values) {
  std::string text;
  for (const double v : values) {
    if (!text.empty()) text += ' ';
    text += exact_text(v);
  }
  return text;
}

// A rectangle stored as "x0 y0 x1 y1".
PixelRect rect_from(const fs::path& file, const OIIO::ImageSpec& spec, const char* name) {
  std::istringstream in(spec.get_string_attribute(attr(name)));
  PixelRect r;
  if (!(in >> r.x0 >> r.y0 >> r.x1 >> r.y1) || r.x1 < r.x0 || r.y1 < r.y0)
    fail(file, attr(name), "expected four pixel coordinates x0 y0 x1 y1");
  return r;
}
std::string rect_text(const PixelRect& r) {
  return std::to_string(r.x0) + " " + std::to_string(r.y0) + " " + std::to_string(r.x1) + " " +
         std::to_string(r.y1);
}

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
    throw InputError("merge: no part covers pixels " + problem->where.text() + " of the " +
                     std::to_string(parts[0].width) + "x" + std::to_string(parts[0].height) +
                     " frame (a missing part?); nothing written");
  throw_input(files[problem->part].string(), "",
              "its crop " + crops[problem->part].text() + " overlaps the crop " +
                  crops[problem->other].text() + " of '" + files[problem->other].string() +
                  "' (at pixels " + problem->where.text() + "); nothing written");
}

}  // namespace

void write_partial_film(const fs::path& file, const PartialFilmHeader& h, const Film& film,
                        const SplatTiles::TileList& splat_tiles) {
  OIIO::ImageSpec spec = film_state_spec(film, h.crop);
  spec.attribute(attr("version"), kPartialFilmVersion);
  spec.attribute(attr("render_key"), h.render_key);
  std::string channel_order;
  for (const std::string& c : film.channels())
    channel_order += (channel_order.empty() ? "" : " ") + c;
  spec.attribute(attr("channels"), channel_order);
  spec.attribute(attr("reconstruction"), reconstruction_name(h.reconstruction));
  spec.attribute(attr("samples_per_pixel"), int(h.samples_per_pixel));
  spec.attribute(attr("splat_tile_count"), std::to_string(h.splat_tile_count));
  spec.attribute(attr("film_exposure"), exact_text(h.film_exposure));
  spec.attribute(attr("view/display_device"), h.view.display_device);
  spec.attribute(attr("view/view_transform"), h.view.view_transform);
  spec.attribute(attr("view/look"), h.view.look);
  spec.attribute(attr("view/exposure_stops"), exact_text(h.view.exposure_stops));
  spec.attribute(attr("view/gamma"), exact_text(h.view.gamma));
  spec.attribute(attr("view/dither_intensity"), exact_text(h.view.dither_intensity));
  spec.attribute(attr("render_seconds"), exact_text(h.render_seconds));
  spec.attribute(attr("dropped_samples"), std::to_string(h.dropped_samples));
  spec.attribute(attr("tiles"), rect_text(h.tiles));
  spec.attribute(attr("tile_seconds"), joined(h.tile_seconds));
  put_metadata(h.metadata, spec);
  const std::vector<uint32_t> pixels = encode_film_state(film, h.crop);
  std::vector<StateImage> images{{spec, pixels.data()}};
  SplatTilesImage tiles;
  if (h.reconstruction == Reconstruction::kSplat) {
    tiles = encode_splat_tiles(splat_tiles, film.channels(), film.width(), film.height());
    images.push_back({tiles.spec, tiles.pixels.data()});
  }
  write_state_images(file, images);
}

PartialFilmHeader read_partial_film_header(const fs::path& file) {
  if (!fs::is_regular_file(file)) fail(file, "", "no such partial film");
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) fail(file, "", "cannot be read as a partial film: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const int version = spec.get_int_attribute(attr("version"));
  if (version > 0 && version != kPartialFilmVersion)
    fail(file, "",
         "a version " + std::to_string(version) + " partial film, this filmback merges version " +
             std::to_string(kPartialFilmVersion) +
             " (an earlier filmback wrote it): render the part again");
  if (version != kPartialFilmVersion)
    fail(file, "",
         "not a filmback partial film (version " + std::to_string(kPartialFilmVersion) +
             "), as `filmback render --tile/--crop` writes");
  PartialFilmHeader h;
  h.width = uint32_t(std::max(spec.full_width, 0)),
  h.height = uint32_t(std::max(spec.full_height, 0));
  if (spec.x < 0 || spec.y < 0 || spec.full_x != 0 || spec.full_y != 0 || h.width == 0 ||
      h.height == 0)
    fail(file, "", "its data or display window is not a part of a frame");
  h.crop = {uint32_t(spec.x), uint32_t(spec.y), uint32_t(spec.x + spec.width),
            uint32_t(spec.y + spec.height)};
  if (h.crop.empty() || h.crop.x1 > h.width || h.crop.y1 > h.height)
    fail(file, "", "its crop " + h.crop.text() + " is not inside its frame");
  h.render_key = spec.get_string_attribute(attr("render_key"));
  h.reconstruction = spec.get_string_attribute(attr("reconstruction")) == "splat"
                         ? Reconstruction::kSplat
                         : Reconstruction::kImportance;
  h.samples_per_pixel = uint32_t(spec.get_int_attribute(attr("samples_per_pixel")));
  {
    std::istringstream count(spec.get_string_attribute(attr("splat_tile_count")));
    if (!(count >> h.splat_tile_count) || h.splat_tile_count > uint64_t(1) << 24)
      fail(file, attr("splat_tile_count"), "expected the number of splat tiles");
  }
  for (const std::string& name : spec.channelnames)
    if (name.size() > 7 && name.rfind("sum.", 0) == 0 && name.substr(name.size() - 3) == ".hi")
      h.channels.push_back(name.substr(4, name.size() - 7));
  // OpenEXR sorts channels by name: the film's order is the metadata's (the integrator's).
  const std::string order = spec.get_string_attribute(attr("channels"));
  if (!order.empty()) {
    h.channels.clear();
    std::istringstream names(order);
    for (std::string c; names >> c;)
      h.channels.push_back(c);
  }
  h.film_exposure = exact_number(file, spec, "film_exposure");
  h.view.display_device = spec.get_string_attribute(attr("view/display_device"));
  h.view.view_transform = spec.get_string_attribute(attr("view/view_transform"));
  h.view.look = spec.get_string_attribute(attr("view/look"));
  h.view.exposure_stops = exact_number(file, spec, "view/exposure_stops");
  h.view.gamma = exact_number(file, spec, "view/gamma");
  h.view.dither_intensity = exact_number(file, spec, "view/dither_intensity");
  h.render_seconds = exact_number(file, spec, "render_seconds");
  h.dropped_samples = uint64_t(exact_number(file, spec, "dropped_samples"));
  h.tiles = rect_from(file, spec, "tiles");
  {
    std::istringstream seconds(spec.get_string_attribute(attr("tile_seconds")));
    for (double s; seconds >> s;)
      h.tile_seconds.push_back(s);
    if (h.tile_seconds.size() != h.tiles.area())
      fail(file, attr("tile_seconds"),
           "expected " + std::to_string(h.tiles.area()) + " tiles' seconds");
  }
  h.metadata = get_metadata(spec);
  return h;
}

void read_partial_film(const fs::path& file, const PartialFilmHeader& h, Film& film,
                       SplatTiles::TileList& splat_tiles) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) fail(file, "", "cannot be read as a partial film: " + OIIO::geterror());
  const auto corrupt = [&](const std::string& why) {
    fail(file, "", "truncated or corrupt partial film: " + why);
  };
  if (const std::string why = decode_film_state(*in, h.crop, film); !why.empty()) corrupt(why);
  if (h.reconstruction != Reconstruction::kSplat) return;
  if (!in->seek_subimage(1, 0)) corrupt("its splat tiles are missing");
  SplatTiles::TileList own;
  if (const std::string why =
          decode_splat_tiles(*in, film.channels(), h.width, h.height, splat_tiles.size(), own);
      !why.empty())
    corrupt(why);
  for (size_t tile = 0; tile < own.size(); ++tile) {
    if (!own[tile]) continue;
    if (splat_tiles[tile])
      fail(file, "",
           "splat tile " + std::to_string(tile) + " is also another part's: the parts overlap");
    if (own[tile]->samples != h.samples_per_pixel)
      corrupt("splat tile " + std::to_string(tile) + " holds " +
              std::to_string(own[tile]->samples) + " of " + std::to_string(h.samples_per_pixel) +
              " samples");
    splat_tiles[tile] = std::move(own[tile]);
  }
}

Film merge_partial_films(const std::vector<fs::path>& files,
                         const std::vector<PartialFilmHeader>& parts) {
  check_parts(files, parts);
  const PartialFilmHeader& first = parts[0];
  Film film(first.width, first.height, first.channels);
  SplatTiles::TileList splat_tiles(first.splat_tile_count);
  for (size_t i = 0; i < parts.size(); ++i)
    read_partial_film(files[i], parts[i], film, splat_tiles);
  if (first.reconstruction == Reconstruction::kSplat) {
    // The crops' own sums only held their parts' tiles: the film is the tiles' sums, added in
    // the whole frame's tile order into an empty film.
    for (size_t tile = 0; tile < splat_tiles.size(); ++tile)
      if (!splat_tiles[tile])
        throw InputError("merge: no part holds splat tile " + std::to_string(tile) +
                         " (a truncated part?); nothing written");
    std::fill_n(film.sums(), film.pixel_count() * film.channels().size(), 0.0);
    std::fill_n(film.weights(), film.pixel_count(), 0.0);
    SplatTiles::add_splat_tiles(splat_tiles, film);
    film.set_sample_count(0, 0, film.width(), film.height(), first.samples_per_pixel);
  }
  return film;
}

}  // namespace fb
