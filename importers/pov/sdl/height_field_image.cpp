#include "importers/pov/sdl/height_field_image.h"

#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "core/image/image_io.h"
#include "core/util/error.h"

namespace fb::pov {

namespace {

struct PngReader {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngReader() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

// The palette indices of a colour-mapped PNG, read through libpng (OpenImageIO expands palettes
// into colours, which lose the index POV-Ray uses); none for any other file. Size checked first.
std::optional<HeightImage> palette_heights(const std::filesystem::path& file, size_t max_pixels) {
  std::unique_ptr<FILE, int (*)(FILE*)> in(std::fopen(file.c_str(), "rb"), std::fclose);
  if (!in) return std::nullopt;
  png_byte signature[8];
  if (std::fread(signature, 1, 8, in.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
    return std::nullopt;
  PngReader reader;
  reader.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!reader.png) return std::nullopt;
  reader.info = png_create_info_struct(reader.png);
  if (!reader.info) return std::nullopt;
  HeightImage image;
  std::vector<png_byte> rows;
  std::vector<png_bytep> row_pointers;
  // libpng reports a broken file by longjmp here; every object above outlives the jump.
  if (setjmp(png_jmpbuf(reader.png)))
    throw InputError(file.string() + ": cannot read the colour-mapped PNG (damaged file)");
  png_init_io(reader.png, in.get());
  png_set_sig_bytes(reader.png, 8);
  png_read_info(reader.png, reader.info);
  if (png_get_color_type(reader.png, reader.info) != PNG_COLOR_TYPE_PALETTE) return std::nullopt;
  image.width = png_get_image_width(reader.png, reader.info);
  image.height = png_get_image_height(reader.png, reader.info);
  if (double(image.width) * image.height > double(max_pixels)) return std::nullopt;
  png_set_packing(reader.png);  // 1, 2 and 4-bit indices one to a byte
  png_read_update_info(reader.png, reader.info);
  rows.resize(size_t(image.width) * image.height);
  for (uint32_t y = 0; y < image.height; ++y)
    row_pointers.push_back(rows.data() + size_t(y) * image.width);
  png_read_image(reader.png, row_pointers.data());
  image.heights.reserve(rows.size());
  for (png_byte index : rows)
    image.heights.push_back(index / 256.0);
  return image;
}

}  // namespace

HeightImage read_height_image(const std::filesystem::path& file, size_t max_pixels) {
  if (std::optional<HeightImage> indexed = palette_heights(file, max_pixels)) return *indexed;
  const Image pixels = read_image(file, max_pixels);  // throws, naming the file and the limit
  HeightImage image{pixels.width, pixels.height, {}};
  image.heights.reserve(size_t(image.width) * image.height);
  const size_t channels = pixels.channels.size();
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      // Rec. 601 luma of a colour image, as POV-Ray's grey value (an alpha channel is not height).
      const double grey = channels >= 3 ? 0.299 * pixels.at(x, y, 0) + 0.587 * pixels.at(x, y, 1) +
                                              0.114 * pixels.at(x, y, 2)
                                        : pixels.at(x, y, 0);
      image.heights.push_back(std::clamp(grey, 0.0, 1.0) * (65535.0 / 65536.0));
    }
  return image;
}

}  // namespace fb::pov
