// What a render's state holds beside its Film: the splat tiles' sums (splatting forms them per
// tile and adds them to the film only when the render ends) and the convergence map (adaptive
// sampling's half buffer and converged flags). A checkpoint saves both with the film, so that a
// resumed render goes on from the very same state (core/film/checkpoint.h); a part writes its
// splat tiles into its partial film (core/film/partial_film.h).
#pragma once

#include <optional>

#include "core/film/adaptive_sampling.h"
#include "core/film/splat_tiles.h"

namespace fb {

struct SamplingState {
  SplatTiles::TileList splat_tiles;           // splatting: a slot per tile of the sample domain
  std::optional<ConvergenceMap> convergence;  // adaptive sampling: the film's size
};

}  // namespace fb
