// A float image with named channels, top row first (docs/conventions.md, "Raster").
#pragma once

#include <algorithm>
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

// Widens `image` by the channels `names`, after its own, zero in every pixel (the host's passes
// beside what the film resolved: Cryptomatte, Vector).
inline void append_channels(Image& image, const std::vector<std::string>& names) {
  const size_t old_n = image.channels.size(), n = old_n + names.size();
  std::vector<float> pixels(size_t(image.width) * image.height * n, 0.f);
  for (size_t pixel = 0; pixel < size_t(image.width) * image.height; ++pixel)
    std::copy_n(image.pixels.data() + pixel * old_n, old_n, pixels.data() + pixel * n);
  image.channels.insert(image.channels.end(), names.begin(), names.end());
  image.pixels = std::move(pixels);
}

}  // namespace fb
