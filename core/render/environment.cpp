#include "core/render/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/math/constants.h"

namespace fb {
namespace {

// The index i with cdf[i] <= u < cdf[i + 1] among `count` bins, and u's fraction within it.
uint32_t find_bin(const double* cdf, uint32_t count, double u, double& fraction) {
  const uint32_t i = uint32_t(std::clamp<ptrdiff_t>(
      std::upper_bound(cdf, cdf + count + 1, u) - cdf - 1, 0, ptrdiff_t(count) - 1));
  const double width = cdf[i + 1] - cdf[i];
  fraction = width > 0 ? std::clamp((u - cdf[i]) / width, 0.0, 1.0 - 1e-9) : 0.5;
  return i;
}

}  // namespace

EnvironmentLight::EnvironmentLight(const EnvironmentMap& map)
    : width_(map.width), height_(map.height), texels_(map.texels) {
  row_cdf_.assign(height_ + 1, 0.0);
  column_cdf_.assign(size_t(height_) * (width_ + 1), 0.0);
  row_weight_.assign(height_, 0.0);
  double luminance_sum = 0;  // weighted by solid angle
  for (uint32_t y = 0; y < height_; ++y) {
    const double sin_theta = std::sin(kPi * (y + 0.5) / height_);
    double* cdf = &column_cdf_[size_t(y) * (width_ + 1)];
    for (uint32_t x = 0; x < width_; ++x) {
      const double weight = std::max(0.f, luminance(texels_[size_t(y) * width_ + x])) * sin_theta;
      cdf[x + 1] = cdf[x] + weight;
    }
    row_weight_[y] = cdf[width_];
    luminance_sum += row_weight_[y];
    for (uint32_t x = 0; x <= width_; ++x)
      cdf[x] = row_weight_[y] > 0 ? cdf[x] / row_weight_[y] : double(x) / width_;
    row_cdf_[y + 1] = row_cdf_[y] + row_weight_[y];
  }
  total_ = row_cdf_[height_];
  for (double& c : row_cdf_)
    c = total_ > 0 ? c / total_ : 0.0;
  // The texels' solid angles sum to 2 pi^2 sin(theta) / (width height) each: 4 pi in all.
  mean_luminance_ = luminance_sum * 2 * kPi * kPi / (double(width_) * height_) / (4 * kPi);
}

Vec2f EnvironmentLight::to_image(Vec3f w) {
  const float xb = w.x, yb = -w.z, zb = w.y;  // glTF (Y up) to Blender (Z up) axes
  float u = 0.5f - std::atan2(yb, xb) / float(2 * kPi);
  u -= std::floor(u);
  const float v = std::acos(std::clamp(zb, -1.f, 1.f)) / float(kPi);
  return {u, v};
}

Vec3f EnvironmentLight::to_direction(Vec2f uv) {
  const double phi = (0.5 - uv.x) * 2 * kPi, theta = uv.y * kPi;
  const double xb = std::sin(theta) * std::cos(phi), yb = std::sin(theta) * std::sin(phi),
               zb = std::cos(theta);
  return {float(xb), float(zb), float(-yb)};
}

Rgb EnvironmentLight::radiance(Vec3f w) const {
  const Vec2f uv = to_image(w);
  // Bilinear between texel centres: wrapping around in longitude, clamped at the poles.
  const float fx = uv.x * float(width_) - 0.5f;
  const float fy = std::clamp(uv.y * float(height_) - 0.5f, 0.f, float(height_ - 1));
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  const auto wrap = [&](int64_t x) { return uint32_t(((x % width_) + width_) % width_); };
  const uint32_t x0 = wrap(int64_t(x0f)), x1 = wrap(int64_t(x0f) + 1);
  const uint32_t y0 = uint32_t(y0f), y1 = std::min(y0 + 1, height_ - 1);
  const auto at = [&](uint32_t x, uint32_t y) { return texels_[size_t(y) * width_ + x]; };
  return (at(x0, y0) * (1 - tx) + at(x1, y0) * tx) * (1 - ty) +
         (at(x0, y1) * (1 - tx) + at(x1, y1) * tx) * ty;
}

float EnvironmentLight::texel_pdf(uint32_t x, uint32_t y) const {
  const double* cdf = &column_cdf_[size_t(y) * (width_ + 1)];
  const double row = row_cdf_[y + 1] - row_cdf_[y], column = cdf[x + 1] - cdf[x];
  return float(row * column * width_ * height_);
}

bool EnvironmentLight::sample(Vec2f u, Vec3f& w, float& pdf) const {
  if (!(total_ > 0)) return false;
  double fy, fx;
  const uint32_t y = find_bin(row_cdf_.data(), height_, u.y, fy);
  const uint32_t x = find_bin(&column_cdf_[size_t(y) * (width_ + 1)], width_, u.x, fx);
  const Vec2f uv(float((x + fx) / width_), float((y + fy) / height_));
  // dω = 2 pi^2 sin(theta) du dv at the point itself: the density in (u, v) is flat in a texel.
  const float sin_theta = std::sin(uv.y * float(kPi));
  if (!(sin_theta > 0.f)) return false;
  w = to_direction(uv);
  pdf = texel_pdf(x, y) / (float(2 * kPi * kPi) * sin_theta);
  return pdf > 0.f;
}

float EnvironmentLight::pdf(Vec3f w) const {
  if (!(total_ > 0)) return 0.f;
  const Vec2f uv = to_image(w);
  const float sin_theta = std::sin(uv.y * float(kPi));
  if (!(sin_theta > 0.f)) return 0.f;
  const uint32_t x = std::min(uint32_t(uv.x * float(width_)), width_ - 1);
  const uint32_t y = std::min(uint32_t(uv.y * float(height_)), height_ - 1);
  return texel_pdf(x, y) / (float(2 * kPi * kPi) * sin_theta);
}

}  // namespace fb
