#include "core/image/byte_quantize.h"

#include <cmath>

namespace fb {
namespace {

// Rows per task of Blender's threaded image conversion (imbuf's IMB_processor_apply_threaded).
constexpr uint32_t kBlenderTaskRows = 64;

// Triangle-shaped noise in [-0.5, 1.5): the sum of two uniform hashes of the position, the common
// GLSL one-liner sin(dot(st, k)) * 43758.5453 modulo 1 (Blender's dither_random_value, after
// Gjøl, "Banding in Games: A Noisy Rant", slide 27). Evaluated in float as Blender does: the
// hash magnifies every rounding of the sine's argument, so the operations and their order matter.
float blender_dither_noise(float s, float t) {
  float hash0 = std::sin(s * 12.9898f + t * 78.233f) * 43758.5453f;
  float hash1 = std::sin(s * 19.9898f + t * 119.233f) * 43798.5453f;
  hash0 -= std::floor(hash0);
  hash1 -= std::floor(hash1);
  return hash0 + hash1 - 0.5f;
}

}  // namespace

uint8_t unit_float_to_byte(float v) {
  if (!(v > 0.f)) return 0;  // NaN too, which Blender's cast leaves undefined
  return v > 1.f - 0.5f / 255.f ? 255 : uint8_t(255.f * v + 0.5f);
}

float blender_dither_offset(uint32_t x, uint32_t y_from_bottom, uint32_t width, uint32_t height,
                            float intensity) {
  if (intensity == 0.f) return 0.f;
  const uint32_t tasks = (height + kBlenderTaskRows - 1) / kBlenderTaskRows;
  const uint32_t task = y_from_bottom / kBlenderTaskRows;
  const uint32_t task_rows =
      task + 1 < tasks ? kBlenderTaskRows : height - kBlenderTaskRows * (tasks - 1);
  const float inv_width = 1.f / float(width), inv_height = 1.f / float(task_rows);
  const float s = float(x) * inv_width;
  const float t = float(y_from_bottom - task * kBlenderTaskRows) * inv_height;
  // float_to_byte_dither_v4 (imbuf/intern/divers.c): 0.0033 scales the noise to about a byte.
  return blender_dither_noise(s, t) * 0.0033f * intensity;
}

}  // namespace fb
