// An equirectangular world image as a light: radiance by direction (bilinear, as Cycles'
// Environment Texture with Linear interpolation) and directions importance-sampled in proportion
// to texel luminance times sin(theta), the texel's solid angle (pbrt 4e §12.5.2, piecewise-constant
// 2-D distribution).
#pragma once

#include <vector>

#include <filmback/vec.h>

#include "core/scene/scene.h"

namespace fb {

class EnvironmentLight {
 public:
  explicit EnvironmentLight(const EnvironmentMap& map);
  // Radiance arriving from world direction `w` (unit, glTF axes: towards where the light comes
  // from).
  Rgb radiance(Vec3f w) const;
  // A direction for u in [0, 1)^2 and its solid-angle pdf; false when the image is black.
  bool sample(Vec2f u, Vec3f& w, float& pdf) const;
  float pdf(Vec3f w) const;  // solid angle
  // Mean luminance over the sphere of directions: pi times it is the irradiance a surface would
  // get from a uniform world as bright, for light selection.
  double mean_luminance() const { return mean_luminance_; }

 private:
  // Image coordinates in [0, 1)^2 (column, row from the top) of a world direction, and back.
  static Vec2f to_image(Vec3f w);
  static Vec3f to_direction(Vec2f uv);
  float texel_pdf(uint32_t x, uint32_t y) const;  // over [0, 1)^2

  uint32_t width_, height_;
  std::vector<Rgb> texels_;
  std::vector<double> row_cdf_;     // height + 1: marginal over rows
  std::vector<double> column_cdf_;  // height rows of width + 1: conditional over columns
  std::vector<double> row_weight_;  // sum of a row's weights
  double total_ = 0, mean_luminance_ = 0;
};

}  // namespace fb
