// The film's raw state in an OpenEXR image, exactly: per pixel and channel the sum of w v, per
// pixel the sum of w (each double as its two 32-bit halves in UINT channels) and the sample count.
// One encoding for checkpoints (checkpoint.h), partial films and their splat tiles
// (partial_film.h).
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/film/film.h"
#include "core/film/pixel_rect.h"

namespace fb {

// The channels, in file order: "sum.C.hi", "sum.C.lo" per film channel C, "weight.hi",
// "weight.lo", then "samples" when `with_counts`.
std::vector<std::string> film_state_channels(const std::vector<std::string>& channels,
                                             bool with_counts);

// One pixel's sums and weight into 2 (channels + 1) words, each double as its bits' high and low
// halves; and back from the words at `index` (the file's positions of film_state_channels' names,
// as OpenEXR sorts channels by name). The read returns false when a value is not finite.
void pack_sums(const double* sums, double weight, size_t channels, uint32_t* out);
bool unpack_sums(const uint32_t* in, const std::vector<int>& index, size_t channels, double* sums,
                 double& weight);

// The film's state over `region`: a UINT32 spec whose data window is the region and display
// window the whole film, and its pixels (film_state_channels with counts).
OIIO::ImageSpec film_state_spec(const Film& film, const PixelRect& region);
std::vector<uint32_t> encode_film_state(const Film& film, const PixelRect& region);

// The file positions of `names` in `spec`; "" or what is missing.
std::string channel_positions(const OIIO::ImageSpec& spec, const std::vector<std::string>& names,
                              std::vector<int>& index);

// The data window of `spec`, its negative origin clamped to 0 (callers refuse one as well).
PixelRect data_window(const OIIO::ImageSpec& spec);

// The current subimage of `in`, whose data window is `region`, as UINT32 words (spec.nchannels
// per pixel, row by row). Returns "" or OpenImageIO's error.
std::string read_state_words(OIIO::ImageInput& in, const PixelRect& region,
                             std::vector<uint32_t>& words);

// One subimage of a file: its spec and its UINT32 pixels.
struct StateImage {
  OIIO::ImageSpec spec;
  const uint32_t* pixels;
};

// Writes `images` as the subimages of the OpenEXR `file`, in order, through a temporary file and
// a rename. Throws InputError naming the file.
void write_state_images(const std::filesystem::path& file, const std::vector<StateImage>& images);

// Reads the current subimage of `in`, a film state over `region` of a film of `film`'s size and
// channels, into `film`. Returns "" or what is wrong (another window, a missing channel, a
// truncated file, a non-finite sum).
std::string decode_film_state(OIIO::ImageInput& in, const PixelRect& region, Film& film);

}  // namespace fb
