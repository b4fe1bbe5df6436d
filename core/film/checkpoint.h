// A render's checkpoint: its raw state in an OpenEXR file, exactly (each double stored as its two
// 32-bit halves in UINT channels), so a resumed render continues from the very same sums and ends
// bit-identical to one that was never stopped (docs/cli.md, "Interrupts and checkpoints").
//
// Version 2. Subimage 0: the film (per pixel and channel the sum of w v, per pixel the sum of w
// and the sample count). Then what the SamplingState holds, each subimage named by its
// "filmback/checkpoint_content": "splat_tiles" (splatting: the tiles' sums and samples taken,
// splat_tiles_exr.h) and "convergence" (adaptive sampling: the half buffer, the converged flags
// and the last check's sample count, convergence_exr.h).
//
// A checkpoint carries a key: a text that names everything that decides the samples (the
// render's settings and the scene's content). Resuming with another key is refused.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/film/film.h"
#include "core/film/pixel_rect.h"
#include "core/film/sampling_state.h"

namespace fb {

// Written through a temporary file and renamed, so an interrupted write never replaces a good
// checkpoint with a broken one. Throws InputError naming the file. A part of a render (docs/cli.md,
// "Parts of a render") saves only `region`, the tiles it renders.
void write_checkpoint(const Film& film, const SamplingState& state, const std::string& key,
                      const std::filesystem::path& file,
                      const std::optional<PixelRect>& region = std::nullopt);

// Loads `file` into `film` and `state`, which must have the checkpoint's size and channels and be
// shaped for the render (RenderJob::make_sampling_state: it tells whether splat tiles and a
// convergence map are expected). Throws InputError naming the file when it cannot be read, is not
// a filmback checkpoint of this version, has another key, or its state is not one a render of
// `samples_per_pixel` in tiles of `tile_size` can have left (sample counts above the target or
// differing within a tile among the pixels still sampled, non-finite sums), or holds another
// region. With splatting the film's sums are left zero: a splat render forms them from its tiles
// when it ends.
void read_checkpoint(const std::filesystem::path& file, const std::string& key,
                     uint32_t samples_per_pixel, uint32_t tile_size, Film& film,
                     SamplingState& state, const std::optional<PixelRect>& region = std::nullopt);

}  // namespace fb
