// Sampling a rectangle uniformly in the solid angle it subtends (Ureña, Fajardo and King 2013, "An
// Area-Preserving Parametrization for Spherical Rectangles", EGSR): Cycles' sampling of
// rectangular area lights (rect_light_sample in Blender 3.4's kernel/light/light.h). Every sample
// has the pdf 1 / solid_angle(), so the noise of a rectangle's direct light does not grow with how
// close or how oblique it is, as it does when points are drawn uniformly over its area.
#pragma once

#include <filmback/vec.h>

namespace fb {

class SphericalRectangle {
 public:
  // The rectangle with one corner at `corner` and orthogonal edges `edge_u` and `edge_v` from it,
  // seen from `origin`. Computed in double: the solid angle is a difference of angles near pi,
  // which single precision loses for a small or distant rectangle.
  SphericalRectangle(Vec3d origin, Vec3d corner, Vec3d edge_u, Vec3d edge_v);
  // Steradians; 0 when the origin lies in the rectangle's plane.
  double solid_angle() const { return solid_angle_; }
  // The point of the rectangle that (u, v) in [0, 1]^2 picks: (u, v) uniform gives points uniform
  // in solid angle.
  Vec3d sample(double u, double v) const;

 private:
  Vec3d origin_, x_, y_, z_;  // the paper's local frame: x, y along the edges, z towards it
  double x0_, x1_, y0_, y1_, z0_;
  double b0_, b1_, k_;  // the paper's constants for inverting the solid angle in u
  double solid_angle_;
};

}  // namespace fb
