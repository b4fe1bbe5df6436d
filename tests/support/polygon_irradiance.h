// Irradiance from a uniformly emitting polygon, in closed form, for the tests that check area
// lights against analytic values.
#pragma once

#include <cmath>
#include <vector>

#include <filmback/vec.h>

namespace fb::test {

// Lambert's formula (1760; Arvo 1995, "Applications of Irradiance Tensors"): the irradiance at a
// point p with unit normal n from a convex polygon of radiance L wholly above p's tangent plane is
// E = L / 2 * |sum_i Theta_i n . u_i|, Theta_i the angle the edge from corner i to i + 1 subtends
// at p and u_i the unit normal of the plane through p and that edge.
inline double polygon_irradiance(const std::vector<Vec3d>& corners, double radiance, Vec3d p,
                                 Vec3d n) {
  double sum = 0;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3d a = normalize(corners[i] - p), b = normalize(corners[(i + 1) % corners.size()] - p);
    const Vec3d c = cross(a, b);
    const double sine = length(c);
    if (!(sine > 0)) continue;  // a zero-length edge subtends nothing
    sum += std::atan2(sine, dot(a, b)) * dot(n, c) / sine;
  }
  return radiance / 2 * std::abs(sum);
}

}  // namespace fb::test
