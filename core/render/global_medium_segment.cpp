#include "core/render/global_medium_segment.h"

#include <algorithm>
#include <cmath>

namespace fb {
namespace {

// Ground fog's density integrated over h from 0: the antiderivative G of 1 below the offset and
// of 1 / (1 + h^2) above (POV-Ray's ComputeGroundFogColour integrates the same way).
double ground_fog_integral(double h) {
  return h <= 0 ? h : std::atan(h);
}

double ground_fog_density(double h) {
  return h <= 0 ? 1 : 1 / (1 + h * h);
}

// Below this change of h along the segment its density is taken as constant (the quotient of
// differences would cancel).
constexpr double kGroundFogFlatSpan = 1e-9;

// Where the physical model stops following an escaping ray: far enough that any fog hides what
// lies beyond, near enough that depths stay finite.
constexpr double kMediumEscapeLength = 1e30;

}  // namespace

double optical_depth(const GlobalMedium& medium, Vec3d origin, Vec3d direction, double length) {
  if (!(medium.distance_m > 0) || !(length > 0)) return 0;
  if (medium.profile == MediumProfile::kConstant) return length / medium.distance_m;
  const double h0 = (dot(origin, medium.up) - medium.offset_m) / medium.altitude_m;
  const double rise = dot(direction, medium.up) / medium.altitude_m;  // dh per metre
  if (std::abs(rise * std::min(length, 1e30)) < kGroundFogFlatSpan)
    return ground_fog_density(h0) * length / medium.distance_m;
  // h1 is +-infinity for a ray that escapes: G(+inf) = pi/2 (a finite depth upwards),
  // G(-inf) = -inf (downwards it hides everything).
  const double h1 = h0 + rise * length;
  return (ground_fog_integral(h1) - ground_fog_integral(h0)) / rise / medium.distance_m;
}

MediumSegment medium_segment(const std::vector<GlobalMedium>& media, MediumModel model,
                             Vec3d origin, Vec3d direction, double length) {
  MediumSegment segment;
  if (model == MediumModel::kPhysical) {
    // One medium of the summed extinction, emitting the depth-weighted mean colour: exact for one
    // fog, or for fogs of one profile (their depths stay in proportion along the segment). An
    // escaping ray is followed for kMediumEscapeLength, so that the fogs that hide it weigh by
    // their extinction there.
    double tau = 0;
    Vec3d weighted{0, 0, 0};
    for (const GlobalMedium& m : media) {
      const double depth =
          optical_depth(m, origin, direction, std::min(length, kMediumEscapeLength));
      tau += depth;
      weighted += Vec3d(m.colour) * depth;
    }
    if (!(tau > 0)) return segment;
    const float through = float(std::exp(-tau));
    segment.transmittance = Rgb{through, through, through};
    segment.emitted = Rgb(weighted * (-std::expm1(-tau) / tau));
    return segment;
  }
  for (const GlobalMedium& m : media) {
    // POV-Ray's ComputeFog: the light behind keeps at least `transmit`, and `filter` of it is
    // tinted by the fog's colour; the fog shows what it hides.
    const double tau = optical_depth(m, origin, direction, length);
    const float kept = std::max(float(std::exp(-tau)), m.transmit);
    const Rgb tint = Rgb{1.f - m.filter, 1.f - m.filter, 1.f - m.filter} + m.colour * m.filter;
    segment.transmittance = segment.transmittance * tint * kept;
    segment.emitted += m.colour * (1.f - kept);
  }
  return segment;
}

MediumSegment RenderMedia::along(const fb_ray& ray, float t_end, MediumModel model) const {
  const Vec3d direction(Vec3f(ray.direction));
  const double speed = std::sqrt(dot(direction, direction));  // metres per unit of t
  if (!(speed > 0)) return {};
  return medium_segment(media_, model, world_from_render_.point(Vec3d(Vec3f(ray.origin))),
                        direction / speed, double(t_end) * speed);
}

}  // namespace fb
