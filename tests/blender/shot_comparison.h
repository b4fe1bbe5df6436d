// A shot's filmback render against Cycles' render of it, pixel and block differences of linear
// RGB, with the noise floor: the same differences between filmback's render and a second one of
// another seed, which is what two unbiased renders at the shot's sample count differ by. Shared
// by the material and Principled shots (blender_material_test.cpp, blender_principled_test.cpp).
#pragma once

#include <filesystem>

#include "core/image/image.h"
#include "core/image/image_comparison.h"
#include "tests/blender/blender_shot.h"

namespace fb::test {

// The comparison itself is core/image/image_comparison.h's, with Cycles' render as the reference
// and a second filmback render of another seed as the noise twin.
using ShotComparison = ImageComparison;

// Renders the shot of `renders` again with filmback with seed 1 (render_shot uses the default
// seed 0) into work_dir/filmback_seed1.exr, and returns it.
Image render_second_seed(const ShotRenders& renders, const std::filesystem::path& work_dir);

// `filmback_seed1` is another filmback render of the same shot (render_second_seed).
inline ShotComparison compare_shot(const Image& cycles, const Image& filmback,
                                   const Image& filmback_seed1) {
  return compare_images(cycles, filmback, filmback_seed1);
}

}  // namespace fb::test
