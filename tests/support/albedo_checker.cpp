#include "support/albedo_checker.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/texture/texture_images.h"
#include "support/png.h"
#include "support/textured_quad.h"

namespace fb::test {
namespace {

// 3 x 3 checks of 4 texels: an odd count of checks keeps the pattern the same under a flip of
// either texture axis, so the tests need not assume which way t runs through the image.
constexpr int kAlbedoChecks = 3, kAlbedoCheckTexels = 4;
constexpr int kAlbedoTexels = kAlbedoChecks * kAlbedoCheckTexels;
constexpr std::array<std::array<unsigned char, 3>, 2> kAlbedoCheckColours = {
    {{200, 64, 32}, {16, 128, 240}}};
constexpr float kAlbedoMetresPerTile = 0.3f, kAlbedoWallDistance = 1.f;
constexpr float kAlbedoOffsetS = 1.f / kAlbedoChecks;  // one check along s: swaps the colours

std::vector<unsigned char> coloured_checker_png() {
  std::vector<unsigned char> rgba;
  for (int y = 0; y < kAlbedoTexels; ++y)
    for (int x = 0; x < kAlbedoTexels; ++x) {
      const auto& c = kAlbedoCheckColours[(x / kAlbedoCheckTexels + y / kAlbedoCheckTexels) % 2];
      rgba.insert(rgba.end(), {c[0], c[1], c[2], 255});
    }
  return png(kAlbedoTexels, kAlbedoTexels, rgba);
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

// Which check colour (0 or 1) pixel (x, y) shows alone, or -1 when it straddles a check's edge.
int albedo_check_in_pixel(uint32_t x, uint32_t y) {
  // The camera at the origin looks down -z with a vertical field of view of 0.5 rad: raster
  // (px, py) sees the wall at x = (2 px / W - 1) h, y = (1 - 2 py / H) h, h = d tan(0.25).
  const float half_extent_m = kAlbedoWallDistance * std::tan(0.25f);
  // The box filter keeps each sample inside its pixel: a pixel whose four corners show the same
  // check, away from its edges, shows that check alone (the map from raster to wall is affine).
  int colour = -2;
  for (const float cx : {0.f, 1.f})
    for (const float cy : {0.f, 1.f}) {
      const float wx = (2.f * (float(x) + cx) / kAlbedoCheckerImagePx - 1.f) * half_extent_m;
      const float wy = (1.f - 2.f * (float(y) + cy) / kAlbedoCheckerImagePx) * half_extent_m;
      const int c = check_colour_at(wx, wy);
      colour = colour == -2 || colour == c ? c : -1;
    }
  return colour;
}

}  // namespace

Scene albedo_checker_wall(const std::filesystem::path& gltf_file) {
  Scene scene =
      textured_quad({{-5.f, -5.f, -kAlbedoWallDistance},
                     {5.f, -5.f, -kAlbedoWallDistance},
                     {5.f, 5.f, -kAlbedoWallDistance},
                     {-5.f, 5.f, -kAlbedoWallDistance}},
                    false, kAlbedoMetresPerTile, kAlbedoTexels, kAlbedoCheckTexels, 1.0, gltf_file);
  // textured_quad's wall emits its checker; here it reflects ours instead.
  scene.images.at(0).bytes = coloured_checker_png();
  Material& material = scene.materials.at(scene.meshes.at(0).material);
  material.textures.emissive.image = kNoImage;
  material.emission = Rgb{};
  material.base_color = Rgb{1.f, 1.f, 1.f};
  material.textures.base_color.image = 0;
  material.textures.base_color.uv_transform = {1, 0, kAlbedoOffsetS, 0, 1, 0};
  return scene;
}

RenderOptions albedo_checker_options() {
  return texture_render_options(kAlbedoCheckerImagePx, kAlbedoCheckerImagePx, 4, true, 1);
}

std::array<int, 2> expect_checker_albedo(const Image& image, const std::string& first_channel) {
  const auto channel = std::find(image.channels.begin(), image.channels.end(), first_channel);
  EXPECT_NE(channel, image.channels.end()) << first_channel;
  if (channel == image.channels.end()) return {};
  const size_t first = size_t(channel - image.channels.begin());
  std::array<int, 2> pixels_checked{};
  for (uint32_t y = 0; y < kAlbedoCheckerImagePx; ++y)
    for (uint32_t x = 0; x < kAlbedoCheckerImagePx; ++x) {
      const int colour = albedo_check_in_pixel(x, y);
      if (colour < 0) continue;
      ++pixels_checked[colour];
      for (size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(image.at(x, y, first + c),
                    srgb_to_linear(kAlbedoCheckColours[colour][c] / 255.f), 1e-5f)
            << first_channel << ": pixel (" << x << ", " << y << ") channel " << c;
    }
  return pixels_checked;
}

}  // namespace fb::test
