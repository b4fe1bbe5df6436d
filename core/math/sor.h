// POV-Ray's surface of revolution, sor { n, <r1, y1>, ..., <rn, yn> } (POV-Ray 3.7 reference,
// "Surface of Revolution"): about the y axis, r(y)^2 a cubic in y on each segment between the
// points 2 to n - 1, interpolating their r^2 with slopes d(r^2)/dy = 2 r dr/dy, dr/dy by central
// differences (the first and last points only steer the end slopes); closed by discs at its
// lowest and highest y unless open.
#pragma once

#include <vector>

#include <filmback/vec.h>

#include "core/math/bounds.h"

namespace fb {

// r^2 = c[0] + c[1] s + c[2] s^2 + c[3] s^3 with s = (y - y0) / (y1 - y0), s in [0, 1]. The next
// segment's y0 is this one's y1, bit for bit.
struct SorSegment {
  double y0 = 0, y1 = 1;
  double c[4] = {0, 0, 0, 0};
};

using Sor = std::vector<SorSegment>;

// The segments through points (r, y), y strictly increasing (the caller checks), at least 4.
Sor sor_from_points(const std::vector<std::pair<double, double>>& points);

double sor_radius_2(const SorSegment& segment, double y);
Bounds3d sor_bounds(const Sor& sor);
// x^2 + z^2 - r(y)^2, < 0 inside (between the caps), for the segment holding y (clamped).
double sor_value(const Sor& sor, Vec3d p);
Vec3d sor_side_gradient(const Sor& sor, Vec3d p);

}  // namespace fb
