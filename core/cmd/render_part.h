// `filmback render --tile I/N [--tile-plan PLAN.json]` or `--crop X0,Y0,X1,Y1`: which part of the
// frame a render takes, and its partial film (docs/cli.md, "Parts of a render").
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/film/partial_film.h"
#include "core/film/pixel_rect.h"
#include "core/render/render_job.h"

namespace fb {

// As typed; all empty: the whole frame.
struct PartRequest {
  std::string tile;                 // "I/N"
  std::string crop;                 // "X0,Y0,X1,Y1"
  std::filesystem::path tile_plan;  // with --tile: take the plan's part I
  bool any() const { return !tile.empty() || !crop.empty(); }
};

// Checks what can be checked before the scene is read (UsageError): the syntax, I < N, one of
// --tile and --crop, --tile-plan only with --tile.
void check_part_request(const PartRequest& request);

// The part's crop in a frame of width x height, or none for the whole frame. UsageError for a
// crop outside the frame or more parts than the frame has tile rows; InputError for a plan that
// cannot be read, has another size or fewer parts than N.
std::optional<PixelRect> part_crop(const PartRequest& request, uint32_t width, uint32_t height);

// Part `index` of `count` of the split without a plan: bands of whole 16-pixel tile rows, their
// heights differing by at most one tile row (the last band may end in a partial row).
PixelRect equal_area_part(uint32_t index, uint32_t count, uint32_t width, uint32_t height);

// What a part's file says beyond its pixels: the key, the finishing information, its timing.
PartialFilmHeader partial_film_header(const RenderJob& job, const RenderResult& result,
                                      const PixelRect& crop, const std::string& render_key,
                                      const ViewSettings& view, double film_exposure);

}  // namespace fb
