// A shot's filmback render against Cycles' render of it, pixel and block differences of linear
// RGB, with the noise floor: the same differences between filmback's render and a second one of
// another seed, which is what two unbiased renders at the shot's sample count differ by. Shared
// by the material and Principled shots (blender_material_test.cpp, blender_principled_test.cpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "core/image/image.h"
#include "tests/blender/blender_shot.h"

namespace fb::test {

struct ShotComparison {
  // Over all pixels and channels: Σ|f − c| / Σc, and Σ|f − f1| / Σc, its noise floor.
  double mean_relative = 0, noise_mean_relative = 0;
  double mean_ratio = 0;  // Σf / Σc
  // Per 16×16 block, of the block's channel sums: |F − C| / C, the worst block and where it is,
  // and the worst block of |F1 − F| / C, its noise floor. A block darker than 2 % of the image's
  // mean block is measured against that instead, so that light where Cycles has none still counts.
  double worst_block = 0, worst_noise_block = 0;
  uint32_t worst_block_x = 0, worst_block_y = 0;
  bool finite = true;  // every value of filmback's render is finite
  // One line: the numbers above, in %.
  std::string summary() const;
};

// Renders the shot of `renders` again with filmback with seed 1 (render_shot uses the default
// seed 0) into work_dir/filmback_seed1.exr, and returns it.
Image render_second_seed(const ShotRenders& renders, const std::filesystem::path& work_dir);

// `filmback_seed1` is another filmback render of the same shot (render_second_seed).
ShotComparison compare_shot(const Image& cycles, const Image& filmback,
                            const Image& filmback_seed1);

}  // namespace fb::test
