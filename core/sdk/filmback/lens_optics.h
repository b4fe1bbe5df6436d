// The optics of a multi-element lens (lens_prescription.h): the paraxial (first-order) properties
// a lens designer quotes, and the exact trace of a ray through its spherical surfaces. The
// `realistic` camera plugin renders through them and reports them to `filmback info`; the
// equations are derived in docs/camera-model.md ("Realistic lenses").
//
// Lens space, in mm: the optical axis is +z pointing towards the object, the film plane is z = 0
// and the rear vertex sits at z = back_distance_mm (the last interface's thickness, which focusing
// sets), as in pbrt-v4's RealisticCamera with z mirrored.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "lens_prescription.h"
#include "vec.h"

namespace fb {

// ------------------------------------------------------------------ paraxial optics
//
// The y-nu trace (W. J. Smith, Modern Lens Design, ch. 2; Kingslake & Johnson, Lens Design
// Fundamentals, ch. 3): at an interface of curvature c between indices n and n',
// n'u' = nu - y (n' - n) c; across a gap of thickness t, y' = y + u' t. A ray parallel to the axis
// at unit height leaves the lens with angle u: the effective focal length is -1/u and the focal
// point lies -y/u past the last vertex.

struct ParaxialLens {
  double efl_mm;     // effective focal length
  double bfl_mm;     // back focal distance: rear vertex to rear focal point
  double ffd_mm;     // front focal distance: front vertex to front focal point (object side)
  double length_mm;  // front vertex to rear vertex
  double
      entrance_pupil_diameter_mm;  // of the axial beam from infinity, whichever aperture limits it
  double fnumber;                  // efl / entrance pupil diameter
  double stop_height_per_height;   // the axial ray's height at the stop per unit height in front
  double exit_pupil_from_rear_mm;  // the stop's paraxial image, + towards the object
};

namespace optics_detail {

// Index of the medium on the film side of interface i, and on its object side.
inline double index_behind(const LensPrescription& lens, size_t i) {
  return lens[i].index;
}
inline double index_in_front(const LensPrescription& lens, size_t i) {
  return i == 0 ? 1.0 : lens[i - 1].index;
}
inline double curvature(const LensInterface& e) {
  return e.is_stop() ? 0.0 : 1.0 / e.radius_mm;
}

struct YNu {
  double y, u;  // height (mm) and angle (slope) after the last interface
};

// Traces a paraxial ray entering the first interface at height y with slope u (towards the film)
// to the last interface. Calls visit(i, y) at each interface.
template <typename Visit>
YNu trace_forward(const LensPrescription& lens, double y, double u, Visit visit) {
  double nu = u;  // in air
  for (size_t i = 0; i < lens.size(); ++i) {
    visit(i, y);
    const double n = index_in_front(lens, i), n_after = index_behind(lens, i);
    nu -= y * (n_after - n) * curvature(lens[i]);
    if (i + 1 < lens.size()) y += nu / n_after * lens[i].thickness_mm;
  }
  return {y, nu};  // the last medium is air
}

// The same from the film side: entering the last interface at height y, slope u (towards the
// object). Reversing the direction negates the curvatures seen by the ray.
inline YNu trace_backward(const LensPrescription& lens, double y, double u) {
  double nu = u;
  for (size_t k = lens.size(); k-- > 0;) {
    const double n = index_behind(lens, k), n_after = index_in_front(lens, k);
    nu -= y * (n_after - n) * -curvature(lens[k]);
    if (k > 0) y += nu / n_after * lens[k - 1].thickness_mm;
  }
  return {y, nu};
}

}  // namespace optics_detail

inline size_t stop_index(const LensPrescription& lens) {
  for (size_t i = 0; i < lens.size(); ++i)
    if (lens[i].is_stop()) return i;
  return lens.size();  // parse_lens_prescription never returns a lens without one
}

// The first-order properties; throws std::invalid_argument for a lens with no positive power.
inline ParaxialLens paraxial_lens(const LensPrescription& lens) {
  using namespace optics_detail;
  ParaxialLens p{};
  for (size_t i = 0; i + 1 < lens.size(); ++i)
    p.length_mm += lens[i].thickness_mm;
  // The axial ray from infinity: focal length, back focus, and which aperture clips it first.
  double pupil_radius = std::numeric_limits<double>::infinity();
  const size_t stop = stop_index(lens);
  const YNu back = trace_forward(lens, 1.0, 0.0, [&](size_t i, double y) {
    if (std::abs(y) > 0)
      pupil_radius = std::min(pupil_radius, lens[i].aperture_diameter_mm / 2 / std::abs(y));
    if (i == stop) p.stop_height_per_height = std::abs(y);
  });
  if (!(back.u < 0))
    throw std::invalid_argument(
        "the lens does not converge light from infinity (its power is "
        "not positive): no real image to put a film at");
  p.efl_mm = -1.0 / back.u;
  p.bfl_mm = -back.y / back.u;
  const YNu front = trace_backward(lens, 1.0, 0.0);
  p.ffd_mm = -front.y / front.u;
  p.entrance_pupil_diameter_mm = 2 * pupil_radius;
  p.fnumber = p.efl_mm / p.entrance_pupil_diameter_mm;
  // A ray from the stop's centre, traced out of the back: where it (extended) crosses the axis.
  double y = 0, nu = 1;
  for (size_t i = stop; i < lens.size(); ++i) {
    const double n = index_in_front(lens, i), n_after = index_behind(lens, i);
    nu -= y * (n_after - n) * curvature(lens[i]);
    if (i + 1 < lens.size()) y += nu / n_after * lens[i].thickness_mm;
  }
  p.exit_pupil_from_rear_mm = y / nu;
  return p;
}

// The lens with its aperture stop closed to f/`fstop` (0: left open); throws std::invalid_argument
// for an f-number below the lens' own. While the stop limits the axial beam the entrance pupil
// scales with it, so the stop's diameter for f/N is 2 (f / 2N) h, h the axial ray's height at the
// stop per unit height in front (ParaxialLens::stop_height_per_height).
inline LensPrescription stopped_down(LensPrescription lens, const ParaxialLens& open,
                                     double fstop) {
  if (fstop == 0) return lens;
  if (fstop < open.fnumber * (1 - 1e-9))
    throw std::invalid_argument("fstop " + std::to_string(fstop) + ": the lens opens to f/" +
                                std::to_string(open.fnumber) + " at most");
  LensInterface& stop = lens[stop_index(lens)];
  stop.aperture_diameter_mm =
      std::min(stop.aperture_diameter_mm, open.efl_mm / fstop * open.stop_height_per_height);
  return lens;
}

// ------------------------------------------------------------------ placing the film
//
// With the film at distance b behind the rear vertex, positions along +z (lens space): rear
// focal point F' = b - BFL, rear principal point H' = F' + EFL, front vertex = b + length, front
// focal point F = front vertex + FFD, front principal point H = F - EFL. An object at distance D
// in front of H images at s' = D f / (D - f) behind H' (Gauss's thick-lens equation in air), so
// focusing at D puts the film at b = BFL + s' - f: the film moves, as in pbrt-v4's
// RealisticCamera::FocusThickLens (which finds H and H' by tracing real rays near the axis).
inline double back_distance_for_focus_mm(const ParaxialLens& p, double focus_distance_mm) {
  if (std::isinf(focus_distance_mm)) return p.bfl_mm;
  const double f = p.efl_mm;
  return p.bfl_mm + focus_distance_mm * f / (focus_distance_mm - f) - f;
}

// Front principal point H, from the film plane, for the film at `back_distance_mm`.
inline double front_principal_z_mm(const ParaxialLens& p, double back_distance_mm) {
  return back_distance_mm + p.length_mm + p.ffd_mm - p.efl_mm;
}

// ------------------------------------------------------------------ real rays

struct LensRay {
  Vec3d origin, direction;  // lens space, mm; the direction unit length
};

// The lens with its film placed, its stop perhaps closed, tracing exact rays through its spheres.
class LensStack {
 public:
  LensStack(LensPrescription lens, double back_distance_mm)
      : lens_(std::move(lens)), vertex_z_mm_(lens_.size()) {
    double z = back_distance_mm;
    for (size_t k = lens_.size(); k-- > 0;) {
      vertex_z_mm_[k] = z;
      if (k > 0) z += lens_[k - 1].thickness_mm;
    }
  }

  const LensPrescription& interfaces() const { return lens_; }
  double rear_z_mm() const { return vertex_z_mm_.back(); }
  double front_z_mm() const { return vertex_z_mm_.front(); }
  double rear_aperture_radius_mm() const { return lens_.back().aperture_diameter_mm / 2; }

  // Follows `ray` through every interface, towards the object if its direction has z > 0, else
  // towards the film; false if an aperture blocks it, it misses a surface or it reflects totally.
  bool trace(LensRay& ray) const {
    const bool to_object = ray.direction.z > 0;
    const size_t count = lens_.size();
    for (size_t k = 0; k < count; ++k) {
      const size_t i = to_object ? count - 1 - k : k;
      const LensInterface& e = lens_[i];
      Vec3d normal;
      double t;
      if (e.is_stop()) {
        t = (vertex_z_mm_[i] - ray.origin.z) / ray.direction.z;
      } else if (!hit_sphere(ray, vertex_z_mm_[i] - e.radius_mm, e.radius_mm, t, normal)) {
        return false;
      }
      if (!(t >= 0)) return false;  // 0: an interface in contact with the previous one
      const Vec3d p = ray.origin + ray.direction * t;
      const double r = e.aperture_diameter_mm / 2;
      if (p.x * p.x + p.y * p.y > r * r) return false;
      ray.origin = p;
      if (e.is_stop()) continue;
      const double n_from = to_object ? lens_[i].index : optics_detail::index_in_front(lens_, i);
      const double n_to = to_object ? optics_detail::index_in_front(lens_, i) : lens_[i].index;
      if (!refract(ray.direction, normal, n_from / n_to)) return false;
    }
    return true;
  }

 private:
  // The surface's hit: of a sphere's two intersections, the one on the cap through the vertex
  // (the vertex faces the film when the radius is negative); the normal faces the ray.
  static bool hit_sphere(const LensRay& ray, double centre_z, double radius, double& t,
                         Vec3d& normal) {
    const Vec3d oc{ray.origin.x, ray.origin.y, ray.origin.z - centre_z};
    const double b = dot(oc, ray.direction), c = dot(oc, oc) - radius * radius;
    const double discriminant = b * b - c;
    if (!(discriminant >= 0)) return false;
    const double root = std::sqrt(discriminant);
    t = (ray.direction.z > 0) == (radius > 0) ? -b + root : -b - root;
    normal = (oc + ray.direction * t) / radius;  // unit, outward for radius > 0
    if (dot(normal, ray.direction) > 0) normal = -normal;
    return true;
  }

  // Snell's law in vector form (Pharr, Jakob & Humphreys, PBR 4th ed., 9.3.2); `eta` = n / n'.
  static bool refract(Vec3d& d, Vec3d n, double eta) {
    const double cos_i = -dot(n, d);
    const double sin2_t = eta * eta * std::max(0.0, 1 - cos_i * cos_i);
    if (sin2_t >= 1) return false;
    d = normalize(d * eta + n * (eta * cos_i - std::sqrt(1 - sin2_t)));
    return true;
  }

  LensPrescription lens_;
  std::vector<double> vertex_z_mm_;
};

}  // namespace fb
