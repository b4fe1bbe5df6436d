// Principled shots against Cycles (principled_shot.py): Blender's own materials (Principled BSDFs
// at roughness 0.2, 0.5 and 0.9 on a ground seen at grazing angles, metal, sheen, clearcoat,
// specular tint, glass, Multiscatter GGX, a Mix Shader of Glossy and Diffuse by a texture, a
// normal-mapped sphere, Emission added to Glossy mixed with Transparent, Principled's Alpha, and
// Blender's default material) under a sun, a point light, a sphere light or a disk light,
// exported with their node trees and rendered by Cycles and by filmback at the same settings.
// The bar is issue 14's: the mean relative difference at most 2 % and every 16x16 block at most
// 5 % above their noise floors, which are the same differences between filmback's render and a
// second one of another seed (shot_comparison.h). Measured numbers: docs/blender.md, "Against
// Cycles: principled_shot.py".
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "tests/blender/blender_shot.h"
#include "tests/blender/shot_comparison.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr double kMeanAboveNoise = 0.02;
constexpr double kBlockAboveNoise = 0.05;

class BlenderPrincipled : public WithBlender<testing::TestWithParam<const char*>> {};

TEST_P(BlenderPrincipled, MatchesCycles) {
  const std::string shot = GetParam();
  const fs::path work = fs::path(FILMBACK_BLENDER_WORK_DIR) / ("principled_" + shot);
  const ShotRenders r = render_shot(blender, shot, work, FILMBACK_PRINCIPLED_SHOT_PY);
  const ShotComparison cmp = compare_shot(r.cycles, r.filmback, render_second_seed(r, work));
  std::printf("%s: %s; Blender %.1f s (Cycles %.1f s), filmback %.1f s\n", shot.c_str(),
              cmp.summary().c_str(), r.blender_s, r.cycles_s, r.filmback_s);
  ASSERT_TRUE(cmp.finite);
  // The anisotropic lobes follow Cycles' default tangent (radial about each object's Z axis):
  // measured 2.57 % against a floor of 2.40 %; an arbitrary tangent gives 3.93 %, which the
  // issue's 2 % above the floor would let through, so this shot is held to 1 %.
  const double mean_above_noise = shot == "anisotropic" ? 0.01 : kMeanAboveNoise;
  EXPECT_LE(cmp.mean_relative, cmp.noise_mean_relative + mean_above_noise);
  EXPECT_LE(cmp.worst_block, cmp.worst_noise_block + kBlockAboveNoise);
}

INSTANTIATE_TEST_SUITE_P(Shots, BlenderPrincipled,
                         testing::Values("roughness_0.2", "roughness_0.5", "roughness_0.9",
                                         "layers", "anisotropic", "glass_mix", "nodes", "default",
                                         "sphere_light", "disk_light"),
                         [](const testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '.') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace fb::test
