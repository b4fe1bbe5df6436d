// A rectangle of film pixels, [x0, x1) x [y0, y1), top-left origin: a part of a render
// (docs/cli.md, "Parts of a render"), a checkpoint's region, a splat tile's reach.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>

namespace fb {

struct PixelRect {
  uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  uint32_t width() const { return x1 - x0; }
  uint32_t height() const { return y1 - y0; }
  uint64_t area() const { return uint64_t(width()) * height(); }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(uint32_t x, uint32_t y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  bool intersects(const PixelRect& o) const {
    return std::max(x0, o.x0) < std::min(x1, o.x1) && std::max(y0, o.y0) < std::min(y1, o.y1);
  }
  bool operator==(const PixelRect&) const = default;
  // "x0,y0,x1,y1", as --crop takes it.
  std::string text() const {
    return std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(x1) + "," +
           std::to_string(y1);
  }
};

// The whole frame of a width x height film.
inline PixelRect whole_frame(uint32_t width, uint32_t height) {
  return {0, 0, width, height};
}

}  // namespace fb
