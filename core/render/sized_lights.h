// Blender's lights with a size, sampled as Cycles 3.4 samples them (kernel/light/light.h of
// Blender 3.4, light_sample and light_sample_from_intersection; the per-type files point.h,
// spot.h, area.h and distant.h, the light tree and sphere-shaped point lights came in later
// releases). Each light both picks points for light sampling and finds the point a ray passes
// through, with the same solid-angle density, so that the two can be combined by multiple
// importance sampling (docs/blender.md, "Lights and world").
//
// Radiance is returned as a scale of the light's intensity (core/scene/scene.h, Light::intensity):
// the light's radiance towards the shading point is intensity x scale (x a spot's falloff, which
// the caller applies).
#pragma once

#include <filmback/vec.h>

namespace fb {

// A point on a light, seen from a shading point (or a ray's origin).
struct SizedLightPoint {
  Vec3f direction;  // unit, from the shading point towards the light
  float distance;   // to the light point; HUGE_VALF for a sun
  float pdf;        // solid angle, of the light's own sampling (without the choice of the light)
  float scale;      // the light's radiance along `direction` over its intensity
};

// A point or spot light of radius r: a disk of radius r centred on the light and turned to face the
// shading point, uniformly bright with radiance I / (pi r^2) (Cycles 3.4: "sphere light (aka,
// aligned disk light)", eval_fac = invarea / (4 pi) with Blender's power P = 4 pi I). A shading
// point sees a disk of area pi r^2 wherever it is, so each sample brings I cos / d^2, as a point
// light at the sampled point would; Blender 4.0 replaced it with a sphere.
class FacingDisk {
 public:
  FacingDisk(Vec3f centre, float radius);
  // A point uniform over the disk facing `p`, at pdf d^2 / (cos pi r^2).
  bool sample(Vec3f p, Vec2f u, SizedLightPoint& out) const;
  // Where the ray (origin, unit direction) crosses the disk facing its origin within (t_min,
  // t_max).
  bool crossed(Vec3f origin, Vec3f direction, float t_min, float t_max, SizedLightPoint& out) const;

 private:
  bool seen(Vec3f p, Vec3f facing, Vec3f q, SizedLightPoint& out) const;
  Vec3f centre_;
  float radius_, inverse_area_;
};

// A sun of angular diameter a: directions through a disk of radius tan(a/2) one unit away, uniform
// over the disk, so with the solid-angle pdf 1 / (pi tan^2(a/2) cos^3 theta); each direction's
// radiance equals its pdf times the sun's irradiance S, so a sample brings S (Cycles' distant
// light: eval_fac = pdf).
class SunDisk {
 public:
  SunDisk(Vec3f towards_sun, float angle_rad);
  bool sample(Vec2f u, SizedLightPoint& out) const;
  // Whether `direction` (of a ray that escapes) lies in the sun's cone.
  bool crossed(Vec3f direction, SizedLightPoint& out) const;

 private:
  bool seen(Vec3f direction, SizedLightPoint& out) const;
  Vec3f towards_;
  float tan_half_, cos_half_, inverse_area_;
};

// A one-sided rectangle or ellipse shining along `normal`, of radiance L (Cycles: P / (4 A)) times
// the spread's attenuation: a rectangle sampled by solid angle over the part of it the spread lets
// reach the shading point (SphericalRectangle; Cycles' rect_light_sample after
// light_spread_clamp_area_light), an ellipse uniformly over its area.
class AreaLight {
 public:
  // Unit, orthogonal axis_u, axis_v and normal; full extents along the axes in metres; the
  // spread's full angle, limited to at least 1 degree as Cycles limits it.
  AreaLight(Vec3f centre, Vec3f axis_u, Vec3f axis_v, Vec3f normal, float size_u, float size_v,
            bool ellipse, double spread_rad);
  float area() const { return area_; }
  bool sample(Vec3f p, Vec2f u, SizedLightPoint& out) const;
  bool crossed(Vec3f origin, Vec3f direction, float t_min, float t_max, SizedLightPoint& out) const;
  // Cycles 3.4's area_light_spread_attenuation: a soft-box grid whose slats hide the light beyond
  // half the spread h from the normal, (tan h - tan theta) / (tan h - h) at angle theta, which
  // keeps the light's power (its cosine-weighted integral over the hemisphere is pi).
  float spread_attenuation(float cos_theta) const;

 private:
  // The rectangle's part within the spread's reach of p, as corner and edges; false if empty.
  bool reach(Vec3f p, Vec3f& corner, Vec3f& edge_u, Vec3f& edge_v) const;
  float solid_angle_pdf(Vec3f p) const;  // the rectangle's sampling density from p
  Vec3f centre_, axis_u_, axis_v_, normal_;
  float half_u_, half_v_, area_;
  bool ellipse_;
  bool spread_limited_;
  double tan_half_spread_, spread_normalization_;
};

}  // namespace fb
