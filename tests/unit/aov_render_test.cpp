// The aov integrator's albedo is the base colour the surface shader evaluates at each hit (the
// value the path integrator's BSDF uses), not the material's untextured factor: a wall with a
// coloured checker as its base-colour texture, read through a KHR_texture_transform offset, seen
// with `--integrator aov`.
#include <gtest/gtest.h>

#include <array>

#include "core/render/render_job.h"
#include "support/albedo_checker.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

TEST(AovRender, AlbedoIsTheTexturedBaseColourAtTheHit) {
  const Scene scene = test::albedo_checker_wall(test::scratch_dir() / "aov_albedo.gltf");
  RenderOptions options = test::albedo_checker_options();
  options.integrator = "aov";
  const Image image = RenderJob(scene, options, test::loader()).run().image;
  const std::array<int, 2> pixels_checked = test::expect_checker_albedo(image, "albedo.R");
  // Both colours are seen over many pixels, so the check is not vacuous.
  EXPECT_GT(pixels_checked[0], 100);
  EXPECT_GT(pixels_checked[1], 100);
}

}  // namespace
}  // namespace fb
