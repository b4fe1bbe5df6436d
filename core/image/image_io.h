// Image files through OpenImageIO. EXR is the master (float, scene-linear Rec.709, camera metadata
// under OpenEXR's standard names); PNG and JPEG are 8-bit display images, made by a
// DisplayTransform (the shot's view transform, or the plain sRGB curve). Files are written to a
// temporary name in the target folder and renamed, so a failure never leaves a broken image behind.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/image/display_transform.h"
#include "core/image/image.h"

namespace fb {

enum class ImageFormat { kExr, kPng, kJpeg };

inline bool is_8_bit(ImageFormat f) {
  return f != ImageFormat::kExr;
}

struct ImageMetadata {
  using Matrix = std::array<float, 16>;  // row-major, column vectors: p' = M p
  std::vector<std::pair<std::string, Matrix>> matrices;
  std::vector<std::pair<std::string, float>> floats;
  std::vector<std::pair<std::string, int>> ints;
  std::vector<std::pair<std::string, std::string>> strings;
};

// Throws UsageError for an extension other than .exr, .png, .jpg or .jpeg (any case).
ImageFormat image_format_for(const std::filesystem::path& file);

// Writes every file, or none: all are written to temporaries first and renamed into place only
// when every one succeeded; if a rename fails, the files that were there before are put back.
// Throws InputError naming the file that failed; no temporary is left behind. 8-bit files get
// `display`'s values.
void write_images(const Image& image, const std::vector<std::filesystem::path>& files,
                  const ImageMetadata& metadata, const DisplayTransform& display = {});

// Whether `file` is a whole image of a finished render: its header opens, and it does not carry
// the mark of an interrupted render ("filmback/interrupted", which EXR keeps; PNG and JPEG keep no
// integer metadata, so an interrupted 8-bit image passes). False for a missing or unreadable file.
bool is_finished_image(const std::filesystem::path& file);

// Throws InputError naming the file, also when it holds more than `max_pixels` pixels.
Image read_image(const std::filesystem::path& file, size_t max_pixels = SIZE_MAX);

}  // namespace fb
