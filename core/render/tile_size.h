#pragma once

#include <cstdint>

namespace fb {

// The render loop's square tile, in pixels: the unit of scheduling, checkpoints, splat tiles and
// of the parts a distributed render is cut into (core/render/render_loop.h).
constexpr uint32_t kTileSize = 16;

}  // namespace fb
