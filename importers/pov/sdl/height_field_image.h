// The heights a POV-Ray height_field reads from an image (POV-Ray 3.7 reference, "Height Field"):
// a colour-mapped image gives its palette index (index * 256 / 65536), any other image its grey
// value scaled to 65535 / 65536, so that heights lie in [0, 1) as in POV-Ray.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace fb::pov {

struct HeightImage {
  uint32_t width = 0, height = 0;
  std::vector<double> heights;  // top row first: heights[row * width + column]
};

// Throws InputError naming the file when it cannot be read or holds more than `max_pixels`.
HeightImage read_height_image(const std::filesystem::path& file, size_t max_pixels);

}  // namespace fb::pov
