// Whether the parts of a render tile its frame: disjoint, and together covering every pixel. For
// tile plans (core/cmd/tile_plan_file.h) and `filmback merge` (docs/cli.md).
#pragma once

#include <optional>
#include <vector>

#include "core/film/pixel_rect.h"

namespace fb {

struct CoverageProblem {
  enum class Kind { kOutside, kOverlap, kGap } kind;
  size_t part = 0, other = 0;  // kOutside: part; kOverlap: part and other (other < part)
  PixelRect where;             // kOverlap: a rectangle both hold; kGap: a rectangle none holds
};

// The first problem, or none. Time and memory grow with the distinct part edges across times
// down (at most (width + 1) x (height + 1) cells), not with the pixels.
std::optional<CoverageProblem> check_coverage(const std::vector<PixelRect>& parts, uint32_t width,
                                              uint32_t height);

}  // namespace fb
