// The aov integrator's albedo is the base colour the surface shader evaluates at each hit (the
// value the path integrator's BSDF uses), not the material's untextured factor: a wall with a
// coloured checker as its base-colour texture, read through a KHR_texture_transform offset, seen
// with `--integrator aov`.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/render/render_job.h"
#include "core/texture/texture_images.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"
#include "support/png.h"
#include "support/textured_quad.h"

namespace fb {
namespace {

// 3 x 3 checks of 4 texels: an odd count of checks keeps the pattern the same under a flip of
// either texture axis, so the test need not assume which way t runs through the image.
constexpr int kAlbedoChecks = 3, kAlbedoCheckTexels = 4;
constexpr int kAlbedoTexels = kAlbedoChecks * kAlbedoCheckTexels;
constexpr std::array<std::array<unsigned char, 3>, 2> kAlbedoCheckColours = {
    {{200, 64, 32}, {16, 128, 240}}};
constexpr float kAlbedoMetresPerTile = 0.3f, kAlbedoWallDistance = 1.f;
constexpr float kAlbedoOffsetS = 1.f / kAlbedoChecks;  // one check along s: swaps the colours
constexpr uint32_t kAlbedoImagePx = 48;

std::vector<unsigned char> coloured_checker_png() {
  std::vector<unsigned char> rgba;
  for (int y = 0; y < kAlbedoTexels; ++y)
    for (int x = 0; x < kAlbedoTexels; ++x) {
      const auto& c = kAlbedoCheckColours[(x / kAlbedoCheckTexels + y / kAlbedoCheckTexels) % 2];
      rgba.insert(rgba.end(), {c[0], c[1], c[2], 255});
    }
  return test::png(kAlbedoTexels, kAlbedoTexels, rgba);
}

// Which check a texture coordinate falls in, along one axis, or -1 when it lies within a texel
// of a check's edge (where bilinear filtering blends the two colours).
int check_along(float st) {
  const float in_checks = st * kAlbedoChecks;
  const float at = in_checks - std::floor(in_checks);
  const float texels_from_edge = std::min(at, 1.f - at) * kAlbedoCheckTexels;
  if (texels_from_edge < 1.f) return -1;
  const int check = int(std::floor(in_checks)) % kAlbedoChecks;
  return check < 0 ? check + kAlbedoChecks : check;
}

// The check colour a point of the wall (x, y) shows after the transform, or -1 near an edge.
int check_colour_at(float x, float y) {
  const int s = check_along(x / kAlbedoMetresPerTile + kAlbedoOffsetS);
  const int t = check_along(y / kAlbedoMetresPerTile);
  return s < 0 || t < 0 ? -1 : (s + t) % 2;
}

TEST(AovRender, AlbedoIsTheTexturedBaseColourAtTheHit) {
  Scene scene = test::textured_quad({{-5.f, -5.f, -kAlbedoWallDistance},
                                     {5.f, -5.f, -kAlbedoWallDistance},
                                     {5.f, 5.f, -kAlbedoWallDistance},
                                     {-5.f, 5.f, -kAlbedoWallDistance}},
                                    false, kAlbedoMetresPerTile, kAlbedoTexels, kAlbedoCheckTexels,
                                    1.0, test::scratch_dir() / "aov_albedo.gltf");
  // textured_quad's wall emits its checker; here it reflects ours instead.
  scene.images.at(0).bytes = coloured_checker_png();
  Material& material = scene.materials.at(scene.meshes.at(0).material);
  material.textures.emissive.image = kNoImage;
  material.emission = Rgb{};
  material.base_color = Rgb{1.f, 1.f, 1.f};
  material.textures.base_color.image = 0;
  material.textures.base_color.uv_transform = {1, 0, kAlbedoOffsetS, 0, 1, 0};

  RenderOptions options = test::texture_render_options(kAlbedoImagePx, kAlbedoImagePx, 4, true, 1);
  options.integrator = "aov";
  const Image image = RenderJob(scene, options, test::loader()).run().image;
  const auto albedo = std::find(image.channels.begin(), image.channels.end(), "albedo.R");
  ASSERT_NE(albedo, image.channels.end());
  const size_t albedo_r = size_t(albedo - image.channels.begin());

  // The camera at the origin looks down -z with a vertical field of view of 0.5 rad: raster
  // (px, py) sees the wall at x = (2 px / W - 1) h, y = (1 - 2 py / H) h, h = d tan(0.25).
  const float half_extent_m = kAlbedoWallDistance * std::tan(0.25f);
  const auto wall_at = [&](float px, float py) {
    return std::array<float, 2>{(2.f * px / kAlbedoImagePx - 1.f) * half_extent_m,
                                (1.f - 2.f * py / kAlbedoImagePx) * half_extent_m};
  };
  std::array<int, 2> pixels_checked{};
  for (uint32_t y = 0; y < kAlbedoImagePx; ++y)
    for (uint32_t x = 0; x < kAlbedoImagePx; ++x) {
      // The box filter keeps each sample inside its pixel: a pixel whose four corners show the
      // same check, away from its edges, shows that check alone (the map from raster to wall is
      // affine).
      int colour = -2;
      for (const float cx : {0.f, 1.f})
        for (const float cy : {0.f, 1.f}) {
          const auto [wx, wy] = wall_at(float(x) + cx, float(y) + cy);
          const int c = check_colour_at(wx, wy);
          colour = colour == -2 || colour == c ? c : -1;
        }
      if (colour < 0) continue;
      ++pixels_checked[colour];
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(image.at(x, y, albedo_r + c),
                    srgb_to_linear(kAlbedoCheckColours[colour][c] / 255.f), 1e-5f)
            << "pixel (" << x << ", " << y << ") channel " << c;
    }
  // Both colours are seen over many pixels, so the check above is not vacuous.
  EXPECT_GT(pixels_checked[0], 100);
  EXPECT_GT(pixels_checked[1], 100);
}

}  // namespace
}  // namespace fb
