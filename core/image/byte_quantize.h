// Blender 3.4's conversion of display-space floats to 8 bits when it saves a render, dither
// included, so that filmback's 8-bit files round as Blender's do (docs/conventions.md, "Images").
#pragma once

#include <cstdint>

namespace fb {

// Blender's unit_float_to_uchar_clamp (blenlib/BLI_math_base_inline.c): 0 at or below 0, 255 above
// 1 - 0.5/255, else 255 v + 0.5 truncated; NaN gives 0.
uint8_t unit_float_to_byte(float v);

// The offset Blender adds to a pixel's three display values before rounding them, for
// Post Processing > Dither `intensity` (0: none). Blender converts the image in tasks of 64 rows
// counted from the bottom (imbuf's IMB_processor_apply_threaded), and each task hashes the pixel's
// position within it: s = x / width, t = row in the task / the task's row count
// (IMB_buffer_byte_from_float, dither_random_value in blenlib/math_color_inline.c). `y_from_bottom`
// is the pixel's row counted from the image's bottom row, as Blender stores images.
float blender_dither_offset(uint32_t x, uint32_t y_from_bottom, uint32_t width, uint32_t height,
                            float intensity);

}  // namespace fb
