#include "core/render/spherical_rectangle.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fb {

SphericalRectangle::SphericalRectangle(Vec3d origin, Vec3d corner, Vec3d edge_u, Vec3d edge_v)
    : origin_(origin) {
  const double length_u = length(edge_u), length_v = length(edge_v);
  x_ = edge_u / length_u;
  y_ = edge_v / length_v;
  z_ = cross(x_, y_);
  const Vec3d d = corner - origin;
  z0_ = dot(d, z_);
  if (z0_ > 0) z_ = -z_, z0_ = -z0_;  // z points from the rectangle towards the origin
  x0_ = dot(d, x_), y0_ = dot(d, y_);
  x1_ = x0_ + length_u, y1_ = y0_ + length_v;
  // Unit normals of the planes through the origin and each edge (the paper's n_0..n_3), and the
  // rectangle's inner angles on the sphere, gamma_i = acos(-n_i . n_i+1); each n_i . n_i+1 is the
  // product of their z components.
  const auto unit_z = [&](double a) { return a / std::sqrt(z0_ * z0_ + a * a); };
  const double n0z = -unit_z(y0_), n1z = unit_z(x1_), n2z = unit_z(y1_), n3z = -unit_z(x0_);
  const double g0 = std::acos(std::clamp(-n0z * n1z, -1.0, 1.0));
  const double g1 = std::acos(std::clamp(-n1z * n2z, -1.0, 1.0));
  const double g2 = std::acos(std::clamp(-n2z * n3z, -1.0, 1.0));
  const double g3 = std::acos(std::clamp(-n3z * n0z, -1.0, 1.0));
  b0_ = n0z, b1_ = n2z;
  k_ = 2 * std::numbers::pi - g2 - g3;
  // The area of a spherical quadrilateral: its angles' sum less 2 pi.
  solid_angle_ = z0_ < 0 && length_u > 0 && length_v > 0 ? std::max(g0 + g1 - k_, 0.0) : 0.0;
}

Vec3d SphericalRectangle::sample(double u, double v) const {
  // The paper's Algorithm 1. The solid angle to the left of x = xu grows linearly with u: invert
  // it for the cosine cu of the angle it leaves at the first corner, then xu.
  const double au = u * solid_angle_ + k_;
  const double fu = (std::cos(au) * b0_ - b1_) / std::sin(au);
  double cu = std::copysign(1.0, fu) / std::sqrt(fu * fu + b0_ * b0_);
  if (!std::isfinite(cu)) cu = 0;  // sin(au) = 0: the edge itself
  cu = std::clamp(cu, -1.0, 1.0);
  const double xu = std::clamp(-cu * z0_ / std::max(std::sqrt(1 - cu * cu), 1e-12), x0_, x1_);
  // Along that line, the height over the sphere's projection is linear in the solid angle.
  const double d = std::sqrt(xu * xu + z0_ * z0_);
  const double h0 = y0_ / std::sqrt(d * d + y0_ * y0_), h1 = y1_ / std::sqrt(d * d + y1_ * y1_);
  const double hv = h0 + v * (h1 - h0), hv2 = hv * hv;
  const double yv = hv2 < 1 - 1e-12 ? hv * d / std::sqrt(1 - hv2) : y1_;
  return origin_ + x_ * xu + y_ * std::clamp(yv, y0_, y1_) + z_ * z0_;
}

}  // namespace fb
