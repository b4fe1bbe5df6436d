// The tile plan file that `filmback tile-plan` writes and `filmback render --tile I/N --tile-plan
// PLAN.json` reads (docs/cli.md, "Parts of a render"):
//   {"format": "filmback-tile-plan", "version": 1, "width": W, "height": H,
//    "parts": [{"crop": [x0, y0, x1, y1], "estimated_seconds": s}, ...]}
// Crops are film pixels, top-left origin, x1/y1 exclusive; together they tile the frame.
#pragma once

#include <filesystem>
#include <vector>

#include "core/film/pixel_rect.h"

namespace fb {

constexpr size_t kMaxParts = 1024;  // parts of one frame: Slurm's default MaxArraySize is 1001

struct TilePlan {
  uint32_t width = 0, height = 0;
  struct Part {
    PixelRect crop;
    double estimated_seconds = 0;
  };
  std::vector<Part> parts;
};

// Throws InputError naming the file and the JSON path when it is not such a plan: a missing or
// mistyped field, a crop outside the frame, crops that overlap or leave pixels uncovered, more
// than kMaxParts parts.
TilePlan read_tile_plan(const std::filesystem::path& file);

// Checks the plan as read_tile_plan does (InputError naming `file`) and writes it atomically.
void write_tile_plan(const TilePlan& plan, const std::filesystem::path& file);

}  // namespace fb
