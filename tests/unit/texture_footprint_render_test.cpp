// Texture lookups filtered by the ray's footprint (core/texture/ray_footprint.h), in whole renders
// of a checkered ground receding to the horizon and of a close-up of a coarse texture. The checker
// is the surface's emission, and the path tracer shows emitters only (max_depth 0): the only noise
// is the texture's integral over each pixel, and the reference is that integral, supersampled at
// the finest level.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/render/render_job.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"
#include "support/textured_quad.h"

namespace fb {
namespace {

using test::textured_quad;

constexpr uint32_t kGroundWidth = 64, kGroundHeight = 40;

std::vector<float> render(const Scene& scene, uint32_t spp, bool footprint, uint64_t seed) {
  const RenderResult result =
      RenderJob(scene,
                test::texture_render_options(kGroundWidth, kGroundHeight, spp, footprint, seed),
                test::loader())
          .run();
  std::vector<float> red;
  for (uint32_t y = 0; y < kGroundHeight; ++y)
    for (uint32_t x = 0; x < kGroundWidth; ++x)
      red.push_back(result.image.at(x, y, 0));
  return red;
}

double rms_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i)
    sum += (double(a[i]) - b[i]) * (a[i] - b[i]);
  return std::sqrt(sum / a.size());
}

// A ground 1 m below the camera out to 200 m, one 64-texel tile of 8-texel checks per metre: all
// but the nearest rows see many checks per pixel. At 1 and 4 samples a pixel, the finest level
// aliases (each sample sees one check: black or white) while the footprint's MIP levels give each
// sample nearly the pixel's mean, so the footprint's error against the reference must be well
// below the finest level's.
TEST(TextureFootprint, MinifiedGroundHasLessErrorThanTheFinestLevel) {
  const Scene scene = textured_quad(
      {{-100.f, -1.f, -0.2f}, {100.f, -1.f, -0.2f}, {100.f, -1.f, -200.f}, {-100.f, -1.f, -200.f}},
      true, 1.f, 64, 8, double(kGroundWidth) / kGroundHeight, test::scratch_dir() / "ground.gltf");
  const std::vector<float> reference = render(scene, 1024, false, 7);
  // The reference's own noise: another 1024-spp render against it, over sqrt(2).
  const double reference_noise =
      rms_difference(reference, render(scene, 1024, false, 8)) / std::sqrt(2.0);
  for (const uint32_t spp : {1u, 4u}) {
    const double finest = rms_difference(render(scene, spp, false, 1), reference);
    const double filtered = rms_difference(render(scene, spp, true, 1), reference);
    std::printf("%u spp: RMS error finest %.4f, footprint %.4f (reference noise %.4f)\n", spp,
                finest, filtered, reference_noise);
    EXPECT_LT(filtered, 0.5 * finest) << spp << " spp";
  }
}

// A coarse 8 x 8 checker (1-texel checks), one tile per metre on a wall 0.5 m ahead: a texel
// covers about 20 pixels, so the footprint is far below a texel and OpenImageIO reads the finest
// level as before. The two renders (same samples) may differ only by the few texels' edges the
// filter smooths, far less than the noise between two seeds of the unfiltered render.
TEST(TextureFootprint, MagnifiedTextureIsUnchanged) {
  const Scene scene = textured_quad(
      {{-5.f, -5.f, -0.5f}, {5.f, -5.f, -0.5f}, {5.f, 5.f, -0.5f}, {-5.f, 5.f, -0.5f}}, false, 1.f,
      8, 1, double(kGroundWidth) / kGroundHeight, test::scratch_dir() / "wall.gltf");
  const std::vector<float> finest = render(scene, 4, false, 1);
  const double difference = rms_difference(render(scene, 4, true, 1), finest);
  const double noise = rms_difference(render(scene, 4, false, 2), finest);
  std::printf("magnified: RMS footprint - finest %.5f, seed-to-seed %.5f\n", difference, noise);
  EXPECT_LT(difference, 0.25 * noise);
}

}  // namespace
}  // namespace fb
