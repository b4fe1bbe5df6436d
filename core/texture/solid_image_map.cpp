#include "core/texture/solid_image_map.h"

#include <algorithm>
#include <cmath>

#include "core/math/constants.h"

namespace fb {
namespace {

double fraction(double v) {
  return v - std::floor(v);
}

// POV-Ray's longitude about y: 0 along +x, a quarter turn at +z, as a fraction of a turn in
// [0, 1).
double turns_about_y(double x, double z) {
  return fraction(std::atan2(z, x) / (2 * kPi));
}

// The image's rows run down from its top, POV-Ray's v up from its bottom: t = 1 - v, wrapped.
Vec2d from_bottom_up(double s, double v) {
  return {fraction(s), fraction(1 - fraction(v))};
}

}  // namespace

std::optional<Vec2d> image_map_position(const SolidImageMap& map, Vec3d p) {
  const auto outside_unit = [](double v) { return v < 0 || v > 1; };
  switch (map.projection) {
    case SolidImageProjection::kPlanar:
      // x across the image, y up it, along z (POV-Ray's default gradient <1, -1, 0>)
      if (map.once && (outside_unit(p.x) || outside_unit(p.y))) return std::nullopt;
      return from_bottom_up(p.x, p.y);
    case SolidImageProjection::kCylindrical:
      if (map.once && outside_unit(p.y)) return std::nullopt;
      if (p.x == 0 && p.z == 0) return std::nullopt;
      return from_bottom_up(turns_about_y(p.x, p.z), p.y);
    case SolidImageProjection::kSpherical: {
      const double r = std::sqrt(dot(p, p));
      if (r == 0) return std::nullopt;
      // latitude: 0 at the south pole, 1 at the north
      const double latitude = 0.5 + std::asin(std::clamp(p.y / r, -1.0, 1.0)) / kPi;
      const double s = p.x == 0 && p.z == 0 ? 0 : turns_about_y(p.x, p.z);
      return from_bottom_up(s, latitude);
    }
    case SolidImageProjection::kTorus: {
      const double ring = std::sqrt(p.x * p.x + p.z * p.z);
      const double across = ring - map.major_radius;  // from the tube's centre line, outwards
      const double tube = std::sqrt(across * across + p.y * p.y);
      if (ring == 0 || tube == 0) return std::nullopt;
      // the angle about the tube: 0 on its inner equator, through the bottom (y < 0) first
      double around = std::acos(std::clamp(-across / tube, -1.0, 1.0));
      if (p.y > 0) around = 2 * kPi - around;
      return from_bottom_up(turns_about_y(p.x, p.z), around / (2 * kPi));
    }
  }
  return std::nullopt;
}

SolidColour image_map_colour(const SolidImageMap& map, Vec3d pattern_point,
                             const TextureImages& images, const SolidColour& fallback) {
  if (map.image == kNoImage) return fallback;
  const std::optional<Vec2d> st = image_map_position(map, pattern_point);
  if (!st) return {{1.f, 1.f, 1.f}, 0.f, 1.f};  // POV-Ray's clear colour off the image
  TextureLookup lookup;
  lookup.image = map.image;
  lookup.s = float(st->x);
  lookup.t = float(st->y);
  // a `once` image is not repeated when interpolating at its edges either
  lookup.wrap_s = lookup.wrap_t = map.once ? TextureWrap::kClamp : TextureWrap::kRepeat;
  lookup.interpolation = map.interpolation;
  lookup.srgb = map.srgb;
  const std::array<float, 4> rgba = images.rgba(lookup);
  Rgb rgb(rgba[0], rgba[1], rgba[2]);
  if (!map.srgb && map.decode_gamma != 1.f)
    for (float* c : {&rgb.x, &rgb.y, &rgb.z})
      *c = std::pow(std::max(*c, 0.f), map.decode_gamma);
  return {rgb, std::clamp(map.filter_all, 0.f, 1.f),
          std::clamp(1.f - rgba[3] + map.transmit_all, 0.f, 1.f)};
}

void mark_image_map_uses(const SolidPattern& pattern, std::vector<uint8_t>& uses) {
  const SolidImageMap& map = pattern.image_map;
  if (pattern.kind == SolidPatternKind::kImageMap && map.image != kNoImage)
    uses.at(map.image) |= map.srgb ? TextureImages::kReadFromSrgb : TextureImages::kReadLinear;
  for (const SolidPattern& entry : pattern.list)
    mark_image_map_uses(entry, uses);
}

}  // namespace fb
