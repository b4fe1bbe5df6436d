// POV-Ray's image_map pigment (POV-Ray 3.7 reference, "Image Map"; the projections of its
// source/core/support/imageutil.cpp): a point of the pattern space projected onto the image, and
// the image's colour there read through OpenImageIO's TextureSystem (core/texture/texture_images.h)
// as filter and transmit (docs/pov.md, "Image maps").
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <filmback/vec.h>

#include "core/scene/solid_texture.h"
#include "core/texture/texture_images.h"

namespace fb {

// The texture position (s, t) (texture_images.h: (0, 0) the image's top-left corner, (1, 1) its
// bottom-right) that `map` reads at `pattern_point`, in [0, 1)^2; none off a `once` image or
// where the projection is undefined (the axis of a sphere, cylinder or torus), which POV-Ray
// shows as clear.
std::optional<Vec2d> image_map_position(const SolidImageMap& map, Vec3d pattern_point);

// The colour at `pattern_point`: linear RGB, filter_all as filter, 1 - alpha + transmit_all as
// transmit; fully transmitting white off the image. With no image (`map.image` kNoImage),
// `fallback`.
SolidColour image_map_colour(const SolidImageMap& map, Vec3d pattern_point,
                             const TextureImages& images, const SolidColour& fallback);

// Marks in `uses` (an entry per Scene::images: TextureImages::kReadLinear, kReadFromSrgb) how the
// image maps of `pattern` and of its list entries read their images.
void mark_image_map_uses(const SolidPattern& pattern, std::vector<uint8_t>& uses);

}  // namespace fb
