// Image files through OpenImageIO. EXR is the master (float, scene-linear Rec.709, camera metadata
// under OpenEXR's standard names); PNG is a preview (sRGB transfer, clamped, 8 bit). Files are
// written to a temporary name in the target folder and renamed, so a failure never leaves a
// broken image behind.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/image/image.h"

namespace fb {

enum class ImageFormat { kExr, kPng };

struct ImageMetadata {
  using Matrix = std::array<float, 16>;  // row-major, column vectors: p' = M p
  std::vector<std::pair<std::string, Matrix>> matrices;
  std::vector<std::pair<std::string, float>> floats;
  std::vector<std::pair<std::string, int>> ints;
  std::vector<std::pair<std::string, std::string>> strings;
};

// Throws UsageError for an extension other than .exr or .png.
ImageFormat image_format_for(const std::filesystem::path& file);

// Writes every file, or none: all are written to temporaries first and renamed into place only
// when every one succeeded; if a rename fails, the files that were there before are put back.
// Throws InputError naming the file that failed; no temporary is left behind.
void write_images(const Image& image, const std::vector<std::filesystem::path>& files,
                  const ImageMetadata& metadata);

// Throws InputError naming the file, also when it holds more than `max_pixels` pixels.
Image read_image(const std::filesystem::path& file, size_t max_pixels = SIZE_MAX);

}  // namespace fb
