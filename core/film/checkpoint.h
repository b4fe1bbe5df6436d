// A render's checkpoint: the film's raw state (per pixel and channel the sum of w v, per pixel the
// sum of w and the sample count) in an OpenEXR file, exactly: each double is stored as its two
// 32-bit halves in UINT channels, so a resumed render continues from the very same sums and ends
// bit-identical to one that was never stopped (docs/cli.md, "Interrupts and checkpoints").
//
// A checkpoint carries a key: a text that names everything that decides the samples (the
// render's settings and the scene's content). Resuming with another key is refused.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/film/film.h"
#include "core/film/pixel_rect.h"

namespace fb {

// Written through a temporary file and renamed, so an interrupted write never replaces a good
// checkpoint with a broken one. Throws InputError naming the file. A part of a render (docs/cli.md,
// "Parts of a render") saves only `region`, the tiles it renders.
void write_checkpoint(const Film& film, const std::string& key, const std::filesystem::path& file,
                      const std::optional<PixelRect>& region = std::nullopt);

// Loads `file` into `film`, which must have the checkpoint's size and channels. Throws InputError
// naming the file when it cannot be read, is not a filmback checkpoint, has another key, or its
// state is not one a render of `samples_per_pixel` in tiles of `tile_size` can have left (sample
// counts differing within a tile or above the target, non-finite sums), or holds another region.
void read_checkpoint(const std::filesystem::path& file, const std::string& key,
                     uint32_t samples_per_pixel, uint32_t tile_size, Film& film,
                     const std::optional<PixelRect>& region = std::nullopt);

}  // namespace fb
