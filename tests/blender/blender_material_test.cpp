// Materials against Blender (material_shot.py): a checker-textured Principled ground under a
// glossy metal and a glossy dielectric sphere, a rough glass sphere, a normal map, an alpha
// cutout and an emissive texture, each shot's node trees exported as Cycles renders them and
// rendered by Cycles and by filmback. Asserted:
//  - texture placement: classified by chromaticity (G/R: the red squares ~0.02, white ones and
//    everything grey or gold above 0.6), no pixel is red in one image and white in the other
//    beyond noise; a flipped or shifted texture would turn half of the ground;
//  - radiometry (shot_comparison.h): the mean relative difference at most 0.5 % and the worst 16x16
//    block at most 1 % above their noise floors (filmback against itself with another seed), the
//    agreement measured at 256 spp with margin (docs/blender.md, "Against Cycles:
//    material_shot.py"); the glass's blocks 5 %, issue 14's bar. Each run prints the numbers.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "tests/blender/blender_shot.h"
#include "tests/blender/checker_pixels.h"
#include "tests/blender/shot_comparison.h"

namespace fb::test {
namespace {

// What a shot must keep: misplaced checker pixels as a fraction of all pixels, and how far the
// mean relative difference and the worst block may lie above their noise floors.
struct Bounds {
  double misplaced_fraction;
  double mean_above_noise;
  double block_above_noise;
};

void compare_with_cycles(const std::filesystem::path& blender, const std::string& shot,
                         const Bounds& bounds) {
  const std::filesystem::path work = std::filesystem::path(FILMBACK_BLENDER_WORK_DIR) / shot;
  const ShotRenders r = render_shot(blender, shot, work);
  const Image &c = r.cycles, &f = r.filmback;
  const ShotComparison cmp = compare_shot(c, f, render_second_seed(r, work));
  ASSERT_TRUE(cmp.finite);

  const auto [misplaced, edge_moved, red] = compare_checkers(c, f);
  const double pixels = double(c.width) * c.height;
  std::printf(
      "%s shot: %zu red-square pixels in Cycles; red/white disagreements %zu (%.3f %%), "
      "edge pixels moved %zu (%.2f %%); %s; Blender %.1f s (Cycles %.1f s), filmback %.1f s\n",
      shot.c_str(), red, misplaced, 100 * misplaced / pixels, edge_moved, 100 * edge_moved / pixels,
      cmp.summary().c_str(), r.blender_s, r.cycles_s, r.filmback_s);
  EXPECT_GT(red, size_t(0.1 * pixels)) << "the checker is not in view";
  EXPECT_LE(misplaced, bounds.misplaced_fraction * pixels);
  EXPECT_LE(cmp.mean_relative, cmp.noise_mean_relative + bounds.mean_above_noise);
  EXPECT_LE(cmp.worst_block, cmp.worst_noise_block + bounds.block_above_noise);
}

using BlenderMaterials = WithBlender<>;

// Measured (256 spp): no misplaced pixel; mean relative difference 1.16 % against a noise floor
// of 1.20 %, worst block 1.07 % against 1.09 %; filmback/Cycles mean 1.0001.
TEST_F(BlenderMaterials, TexturedGroundAndGlossySpheresMatchCycles) {
  compare_with_cycles(blender, "materials", {0.003, 0.005, 0.01});
}

// A rough glass sphere over the checker: the refracted checker lands where Cycles puts it.
// Measured: 0.79 % against 0.92 %; the worst block, where the sphere focuses the sun, 5.34 %
// against filmback's 2.45 %: Cycles' render is the noisier there (at 1024 spp 2.21 % against
// 1.45 %, falling as noise does), hence issue 14's 5 % above the floor for blocks.
TEST_F(BlenderMaterials, RoughGlassSphereMatchesCycles) {
  compare_with_cycles(blender, "glass", {0.003, 0.005, 0.05});
}

// A normal-mapped ground (ridges along the image's x and y): a tangent or bitangent the wrong
// way round lights the other flank of each ridge. Measured: 0.40 % against 0.49 %, worst block
// 0.13 % against 0.12 %; with the normal map's green channel inverted (the bitangent flipped)
// 7.4 % and 28 %.
TEST_F(BlenderMaterials, NormalMappedGroundMatchesCycles) {
  compare_with_cycles(blender, "normal_map", {0.003, 0.005, 0.01});
}

// A card cut out by its texture's alpha (the Principled BSDF's Alpha: a mix with a Transparent
// BSDF in both renderers): its holes and its shadow's holes where Cycles has them (the checker
// seen through a hole that filmback filled would count as misplaced). Measured: 0.39 % against
// 0.45 %, worst block 0.09 % against 0.16 %.
TEST_F(BlenderMaterials, AlphaCutoutMatchesCycles) {
  compare_with_cycles(blender, "alpha", {0.003, 0.005, 0.01});
}

// The ground lit only by a card emitting the checker texture (the Principled BSDF's Emission at
// strength 4): the texture's own pixels and the light it casts, light sampling evaluating the
// texture where it samples the card. Measured: 0.68 % against 0.75 %, worst block 1.28 % against
// 0.91 %.
TEST_F(BlenderMaterials, EmissiveTextureMatchesCycles) {
  compare_with_cycles(blender, "emission", {0.003, 0.005, 0.01});
}

}  // namespace
}  // namespace fb::test
