// The images a scene's materials read, as MIP-mapped textures of OpenImageIO's TextureSystem
// (levels averaged in linear light, tiled, cached), and one lookup: RGBA at a texture position,
// filtered over the ray's footprint (docs/architecture.md, "Texture filtering"). Shared by glTF's
// materials (core/texture/surface_shader.cpp) and Blender's shader graphs
// (core/texture/graph_shader.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/scene/scene.h"
#include "core/texture/surface_point.h"

namespace fb {

struct TextureLookup {
  uint32_t image = kNoImage;
  float s = 0.f,
        t = 0.f;  // texture position: (0, 0) the image's top-left corner, (1, 1) bottom-right
  // The footprint: the change of (s, t) per raster pixel along x and y. Zero reads the finest
  // level; otherwise OpenImageIO picks the MIP level and filters anisotropically over it.
  float ds_dx = 0.f, dt_dx = 0.f, ds_dy = 0.f, dt_dy = 0.f;
  TextureWrap wrap_s = TextureWrap::kRepeat, wrap_t = TextureWrap::kRepeat;
  TextureInterpolation interpolation = TextureInterpolation::kLinear;
  bool srgb = false;  // decode the colour channels from sRGB (the image must be opened so)

  TextureLookup() = default;
  // At `position` (core/texture/surface_point.h), with its footprint.
  TextureLookup(uint32_t image_index, const TexturePosition& position)
      : image(image_index),
        s(position.st.x),
        t(position.st.y),
        ds_dx(position.dst_dx.x),
        dt_dx(position.dst_dx.y),
        ds_dy(position.dst_dy.x),
        dt_dy(position.dst_dy.y) {}
};

class TextureImages {
 public:
  // How a material reads an image (bits of `uses`): its values as they are, or its colour
  // channels decoded from sRGB. Each way is its own MIP-mapped texture, filtered in linear values.
  static constexpr uint8_t kReadLinear = 1, kReadFromSrgb = 2;
  // Opens every image of `scene` that `uses` marks (one entry per image: kReadLinear and/or
  // kReadFromSrgb, or 0); an image that cannot be read or is too large is an InputError naming
  // it.
  TextureImages(const Scene& scene, const std::vector<uint8_t>& uses);
  ~TextureImages();
  TextureImages(const TextureImages&) = delete;
  TextureImages& operator=(const TextureImages&) = delete;

  // Straight (unassociated) RGBA; grey images are spread to RGB, a missing alpha is 1.
  std::array<float, 4> rgba(const TextureLookup& lookup) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// sRGB transfer function, decoding (IEC 61966-2-1).
float srgb_to_linear(float v);

}  // namespace fb
