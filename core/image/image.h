// A float image with named channels, top row first (docs/conventions.md, "Raster").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fb {

struct Image {
  uint32_t width = 0, height = 0;
  std::vector<std::string> channels;
  std::vector<float> pixels;  // (y * width + x) * channels.size() + c

  float at(uint32_t x, uint32_t y, size_t c) const {
    return pixels[(size_t(y) * width + x) * channels.size() + c];
  }
};

}  // namespace fb
