#include "core/render/light_bounds.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/math/constants.h"
#include "core/math/safe_math.h"

namespace fb {
namespace {

// cos(max(0, a - b)) and sin(max(0, a - b)) from the sines and cosines of a and b (pbrt 4e
// §12.6.3: the angles stay in [0, pi], so a > b is cos a < cos b).
float cos_difference_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 1.f : cos_a * cos_b + sin_a * sin_b;
}
float sin_difference_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 0.f : sin_a * cos_b - cos_a * sin_b;
}

// v turned by `angle` about the unit `axis` (Rodrigues' rotation formula).
Vec3f rotated(Vec3f v, Vec3f axis, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.f - c));
}

struct Cone {
  Vec3f axis;
  float cos_theta;
};

// The smallest cone holding both (pbrt 4e §3.8.4).
Cone cone_union(Cone a, Cone b) {
  const float theta_a = safe_acos(a.cos_theta), theta_b = safe_acos(b.cos_theta);
  const float theta_d = safe_acos(dot(a.axis, b.axis));
  if (std::min(theta_d + theta_b, kPiF) <= theta_a) return a;
  if (std::min(theta_d + theta_a, kPiF) <= theta_b) return b;
  const float theta_o = 0.5f * (theta_a + theta_d + theta_b);
  if (theta_o >= kPiF) return {a.axis, -1.f};
  const Vec3f turn_axis = cross(a.axis, b.axis);
  if (!(dot(turn_axis, turn_axis) > 0.f)) return {a.axis, -1.f};
  const Vec3f axis = rotated(a.axis, normalize(turn_axis), theta_o - theta_a);
  return {normalize(axis), std::cos(theta_o)};
}

}  // namespace

LightBounds union_of(const LightBounds& a, const LightBounds& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  const Cone cone = cone_union({a.axis, a.cos_theta_o}, {b.axis, b.cos_theta_o});
  LightBounds u;
  u.lo = min(a.lo, b.lo);
  u.hi = max(a.hi, b.hi);
  u.intensity = a.intensity + b.intensity;
  u.axis = cone.axis;
  u.cos_theta_o = cone.cos_theta;
  u.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  u.two_sided = a.two_sided || b.two_sided;
  return u;
}

float importance(const LightBounds& bounds, Vec3f p) {
  if (bounds.empty()) return 0.f;
  const Vec3f centre = bounds.centre();
  const Vec3f half_diagonal = (bounds.hi - bounds.lo) * 0.5f;
  const float radius2 = dot(half_diagonal, half_diagonal);
  const Vec3f from_centre = p - centre;
  const float distance2 = dot(from_centre, from_centre);
  // Inside the box's bounding sphere every direction may be the light's (theta_b = pi).
  if (!(distance2 > radius2)) return bounds.intensity / std::max(radius2, 1e-12f);
  const Vec3f wi = from_centre / std::sqrt(distance2);
  float cos_theta_w = dot(bounds.axis, wi);
  if (bounds.two_sided) cos_theta_w = std::abs(cos_theta_w);
  const float sin_theta_w = safe_sqrt(1.f - cos_theta_w * cos_theta_w);
  // The box's angular radius from p, by its bounding sphere.
  const float sin2_theta_b = radius2 / distance2;
  const float cos_theta_b = safe_sqrt(1.f - sin2_theta_b), sin_theta_b = std::sqrt(sin2_theta_b);
  const float sin_theta_o = safe_sqrt(1.f - bounds.cos_theta_o * bounds.cos_theta_o);
  // theta_x = theta_w - theta_o, then theta' = theta_x - theta_b, each clamped at 0.
  const float cos_theta_x =
      cos_difference_clamped(sin_theta_w, cos_theta_w, sin_theta_o, bounds.cos_theta_o);
  const float sin_theta_x =
      sin_difference_clamped(sin_theta_w, cos_theta_w, sin_theta_o, bounds.cos_theta_o);
  const float cos_theta_p =
      cos_difference_clamped(sin_theta_x, cos_theta_x, sin_theta_b, cos_theta_b);
  if (cos_theta_p <= bounds.cos_theta_e) return 0.f;
  return bounds.intensity * cos_theta_p / distance2;
}

float orientation_cost(const LightBounds& bounds, int axis_index) {
  const float theta_o = safe_acos(bounds.cos_theta_o), theta_e = safe_acos(bounds.cos_theta_e);
  const float theta_w = std::min(theta_o + theta_e, kPiF);
  const float sin_theta_o = safe_sqrt(1.f - bounds.cos_theta_o * bounds.cos_theta_o);
  // The cosine-weighted solid angle of the directions light can leave in (pbrt 4e eq. 12.23).
  const float m_omega = 2.f * kPiF * (1.f - bounds.cos_theta_o) +
                        0.5f * kPiF *
                            (2.f * theta_w * sin_theta_o - std::cos(theta_o - 2.f * theta_w) -
                             2.f * theta_o * sin_theta_o + bounds.cos_theta_o);
  const Vec3f d = bounds.hi - bounds.lo;
  const float area = 2.f * (d.x * d.y + d.y * d.z + d.z * d.x);
  const float thinness = d[axis_index] > 0.f ? max_component(d) / d[axis_index] : 1.f;
  return bounds.intensity * m_omega * thinness * area;
}

}  // namespace fb
