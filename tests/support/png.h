// Small PNG images for texture tests, encoded by OpenImageIO.
#pragma once

#include <vector>

namespace fb::test {

// The bytes of a PNG of `width` x `height` 8-bit RGBA pixels (top row first), straight alpha as
// glTF's PNGs hold it.
std::vector<unsigned char> png(int width, int height, const std::vector<unsigned char>& rgba);

}  // namespace fb::test
