#include "core/render/sized_lights.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <filmback/geometry.h>
#include <filmback/sampling.h>

#include "core/math/constants.h"
#include "core/render/spherical_rectangle.h"

namespace fb {
namespace {

// The direction and distance from p to a light point q, and the cosine at q between the light's
// normal there and q -> p (0 where q turns away from p).
float towards(Vec3f p, Vec3f q, Vec3f normal, SizedLightPoint& out) {
  const Vec3f d = q - p;
  const float distance2 = dot(d, d);
  if (!(distance2 > 0.f)) return 0.f;
  out.distance = std::sqrt(distance2);
  out.direction = d / out.distance;
  return std::max(0.f, -dot(normal, out.direction));
}

}  // namespace

FacingDisk::FacingDisk(Vec3f centre, float radius)
    : centre_(centre), radius_(radius), inverse_area_(1.f / (kPiF * radius * radius)) {}

// q on the disk facing p (unit `facing`, from the centre towards p): the area pdf 1 / (pi r^2) in
// solid angle, d^2 / (cos pi r^2), with cos the angle between the disk's normal and q -> p.
bool FacingDisk::seen(Vec3f p, Vec3f facing, Vec3f q, SizedLightPoint& out) const {
  const float cosine = towards(p, q, facing, out);
  if (!(cosine > 0.f)) return false;
  out.pdf = out.distance * out.distance * inverse_area_ / cosine;
  out.scale = inverse_area_;
  return std::isfinite(out.pdf);
}

bool FacingDisk::sample(Vec3f p, Vec2f u, SizedLightPoint& out) const {
  const Vec3f to_p = p - centre_;
  const float distance = length(to_p);
  if (!(distance > 0.f)) return false;
  const Vec3f facing = to_p / distance;
  const Vec2f disk = sample_concentric_disk(u);
  return seen(p, facing, centre_ + Frame(facing).to_world({disk.x, disk.y, 0.f}) * radius_, out);
}

bool FacingDisk::crossed(Vec3f origin, Vec3f direction, float t_min, float t_max,
                         SizedLightPoint& out) const {
  const Vec3f to_origin = origin - centre_;
  const float distance = length(to_origin);
  if (!(distance > 0.f)) return false;
  const Vec3f facing = to_origin / distance;
  const float approach = dot(direction, facing);
  if (!(approach < 0.f)) return false;
  const float t = -distance / approach;  // to the disk's plane, through the centre
  if (!(t > t_min && t < t_max)) return false;
  const Vec3f off_centre = origin + direction * t - centre_;
  if (dot(off_centre, off_centre) > radius_ * radius_) return false;
  out.direction = direction;
  out.distance = t;
  out.pdf = t * t * inverse_area_ / -approach;
  out.scale = inverse_area_;
  return std::isfinite(out.pdf);
}

SunDisk::SunDisk(Vec3f towards_sun, float angle_rad)
    : towards_(towards_sun),
      tan_half_(std::tan(angle_rad / 2)),
      cos_half_(std::cos(angle_rad / 2)),
      inverse_area_(1.f / (kPiF * tan_half_ * tan_half_)) {}

// A point at distance 1 / cos theta on the plane one unit away sees an area element dA as the
// solid angle dA cos^3 theta, so the disk's uniform area pdf is 1 / (pi tan^2 cos^3) in solid
// angle.
bool SunDisk::seen(Vec3f direction, SizedLightPoint& out) const {
  const float cosine = dot(towards_, direction);
  if (!(cosine > 0.f)) return false;
  out.direction = direction;
  out.distance = HUGE_VALF;
  out.pdf = inverse_area_ / (cosine * cosine * cosine);
  out.scale = out.pdf;
  return std::isfinite(out.pdf);
}

bool SunDisk::sample(Vec2f u, SizedLightPoint& out) const {
  const Vec2f disk = sample_concentric_disk(u);
  return seen(normalize(towards_ + Frame(towards_).to_world({disk.x, disk.y, 0.f}) * tan_half_),
              out);
}

bool SunDisk::crossed(Vec3f direction, SizedLightPoint& out) const {
  return dot(towards_, direction) >= cos_half_ && seen(direction, out);
}

AreaLight::AreaLight(Vec3f centre, Vec3f axis_u, Vec3f axis_v, Vec3f normal, float size_u,
                     float size_v, bool ellipse, double spread_rad)
    : centre_(centre),
      axis_u_(axis_u),
      axis_v_(axis_v),
      normal_(normal),
      half_u_(size_u / 2),
      half_v_(size_v / 2),
      area_(size_u * size_v * (ellipse ? kPiF / 4 : 1.f)),
      ellipse_(ellipse) {
  // Cycles' scene/light.cpp: spread limited to at least 1 degree; 180 degrees leaves the light
  // unrestricted. In double: tan h - h loses single precision's digits for small spreads.
  const double half = std::max(spread_rad, std::numbers::pi / 180) / 2;
  spread_limited_ = half < std::numbers::pi / 2;
  tan_half_spread_ = spread_limited_ ? std::tan(half) : 0.0;
  spread_normalization_ = spread_limited_ ? 1 / (tan_half_spread_ - half) : 1.0;
}

float AreaLight::spread_attenuation(float cos_theta) const {
  if (!spread_limited_) return 1.f;
  if (!(cos_theta > 0.f)) return 0.f;
  const double tan_theta =
      std::sqrt(std::max(0.0, 1.0 - double(cos_theta) * cos_theta)) / cos_theta;
  return float(std::max(0.0, (tan_half_spread_ - tan_theta) * spread_normalization_));
}

// Cycles' light_spread_clamp_area_light: a point of the light at angle theta from p's foot on the
// light's plane lies tan(theta) times p's height from that foot, so beyond height x tan(h) the
// spread hides it; the rectangle is cut to the square about the foot that holds that circle.
bool AreaLight::reach(Vec3f p, Vec3f& corner, Vec3f& edge_u, Vec3f& edge_v) const {
  float min_u = -half_u_, max_u = half_u_, min_v = -half_v_, max_v = half_v_;
  if (spread_limited_) {
    const Vec3f from_centre = p - centre_;
    const float height = dot(normal_, from_centre);
    const float radius = float(height * tan_half_spread_);
    const float foot_u = dot(axis_u_, from_centre), foot_v = dot(axis_v_, from_centre);
    min_u = std::max(min_u, foot_u - radius), max_u = std::min(max_u, foot_u + radius);
    min_v = std::max(min_v, foot_v - radius), max_v = std::min(max_v, foot_v + radius);
    if (!(min_u < max_u && min_v < max_v)) return false;
  }
  corner = centre_ + axis_u_ * min_u + axis_v_ * min_v;
  edge_u = axis_u_ * (max_u - min_u);
  edge_v = axis_v_ * (max_v - min_v);
  return true;
}

bool AreaLight::sample(Vec3f p, Vec2f u, SizedLightPoint& out) const {
  if (!(dot(p - centre_, normal_) > 0.f)) return false;  // one-sided: p must be in front
  Vec3f q;
  float solid_angle = 0.f;
  if (ellipse_) {
    const Vec2f disk = sample_concentric_disk(u);
    q = centre_ + axis_u_ * (disk.x * half_u_) + axis_v_ * (disk.y * half_v_);
  } else {
    Vec3f corner, edge_u, edge_v;
    if (!reach(p, corner, edge_u, edge_v)) return false;
    const SphericalRectangle rectangle{Vec3d(p), Vec3d(corner), Vec3d(edge_u), Vec3d(edge_v)};
    solid_angle = float(rectangle.solid_angle());
    if (!(solid_angle > 0.f)) return false;
    q = Vec3f(rectangle.sample(u.x, u.y));
  }
  const float cosine = towards(p, q, normal_, out);
  if (!(cosine > 0.f)) return false;
  // An ellipse's area pdf 1 / A in solid angle; a rectangle's 1 / (the solid angle sampled).
  out.pdf = ellipse_ ? out.distance * out.distance / (cosine * area_) : 1.f / solid_angle;
  out.scale = spread_attenuation(cosine);
  return out.scale > 0.f && std::isfinite(out.pdf);
}

float AreaLight::solid_angle_pdf(Vec3f p) const {
  Vec3f corner, edge_u, edge_v;
  if (!reach(p, corner, edge_u, edge_v)) return 0.f;
  const double solid_angle =
      SphericalRectangle(Vec3d(p), Vec3d(corner), Vec3d(edge_u), Vec3d(edge_v)).solid_angle();
  return solid_angle > 0 ? float(1 / solid_angle) : 0.f;
}

bool AreaLight::crossed(Vec3f origin, Vec3f direction, float t_min, float t_max,
                        SizedLightPoint& out) const {
  const float approach = dot(direction, normal_);
  if (!(approach < 0.f)) return false;  // one-sided: only rays against its normal meet it
  const float t = dot(centre_ - origin, normal_) / approach;
  if (!(t > t_min && t < t_max)) return false;
  const Vec3f off_centre = origin + direction * t - centre_;
  const float u = dot(axis_u_, off_centre) / half_u_, v = dot(axis_v_, off_centre) / half_v_;
  if (ellipse_ ? u * u + v * v > 1.f : std::abs(u) > 1.f || std::abs(v) > 1.f) return false;
  out.direction = direction;
  out.distance = t;
  out.scale = spread_attenuation(-approach);
  // Every point the spread lets reach the origin lies in the part reach() cuts, so the density
  // is that of the rectangle sample() draws from.
  out.pdf = ellipse_ ? t * t / (-approach * area_) : solid_angle_pdf(origin);
  return out.scale > 0.f && out.pdf > 0.f && std::isfinite(out.pdf);
}

}  // namespace fb
