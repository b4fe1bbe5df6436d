// Cycles' panoramic projections (Blender's Camera > Panoramic types), the maths the panorama camera
// plugins share and their tests check (docs/camera-model.md, "Panoramic cameras").
//
// Cycles maps a raster position to "film" coordinates (u, v) in [0,1]^2, u rightwards and v
// upwards, then (u, v) to a direction (Cycles 3.4 kernel/camera/projection.h,
// panorama_to_direction; Blender 4.x adds central cylindrical and the equiangular cubemap face).
// Cycles' panorama space looks down +X with +Z up (blender/camera.cpp, blender_camera_matrix);
// the functions here return directions in filmback's camera space, looking down -Z with +Y up, the
// two related by (x, y, z)_filmback = (-y, z, -x)_Cycles (mirror ball: (x, z, y)_Cycles). A
// direction of zero length means "no ray": outside a fisheye's circle, a mirror ball's disc or a
// polynomial lens's field of view.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <string>

#include "camera_projection.h"
#include "plugin_abi.h"
#include "plugin_sdk.h"
#include "sampling.h"
#include "vec.h"

namespace fb::panorama {

constexpr double kPi = std::numbers::pi;

// Film coordinates: u rightwards, v upwards, [0,1]^2 over the image.
struct Film {
  double u, v;
};

// A full (not cropped) render's view plane is [0,1]^2 moved by the lens shift, unscaled
// (Cycles blender/camera.cpp, blender_camera_viewplane for CAMERA_PANORAMA); Cycles' raster y
// counts from the bottom row, filmback's from the top.
inline Film film_from_raster(const fb_camera_setup& s, double x_px, double y_px) {
  return {x_px / s.image_width_px + s.shift_x, 1.0 - y_px / s.image_height_px + s.shift_y};
}
inline Vec2d raster_from_film(const fb_camera_setup& s, Film f) {
  return {(f.u - s.shift_x) * s.image_width_px, (1.0 - f.v + s.shift_y) * s.image_height_px};
}

// The sensor's imaged extent in mm, Cycles' sensorwidth/sensorheight for the equisolid and
// polynomial fisheyes (blender/camera.cpp, blender_camera_sync): the fitted sensor side, and the
// other side in the image's aspect. The focal length plays no part.
inline Vec2d imaged_sensor_mm(const fb_camera_setup& s) {
  const double sensor = fitted_sensor_mm(s);
  const double aspect = s.image_width_px * s.pixel_aspect / s.image_height_px;
  return fits_horizontally(s) ? Vec2d{sensor, sensor / aspect} : Vec2d{sensor * aspect, sensor};
}
// Why the imaged sensor cannot be used, or nullptr.
inline const char* imaged_sensor_problem(const fb_camera_setup& s) {
  const Vec2d mm = imaged_sensor_mm(s);
  return mm.x > 0 && mm.y > 0 && mm.x < 1e6 && mm.y < 1e6
             ? nullptr
             : "the sensor size and pixel aspect must be positive and finite";
}

// ------------------------------------------------------------------ fisheyes
//
// A fisheye maps a point at radius r from the image centre, in the direction (x, y)/r on the film,
// to the direction at angle theta(r) from the view axis in the same azimuth (Cycles'
// fisheye_to_direction). At r = 0 Cycles takes the azimuth +y, which matters only when theta(0)
// is not 0 (a polynomial's k0).
inline Vec3d fisheye_direction(double theta, double x, double y) {
  const double r = std::hypot(x, y);
  const double ex = r > 0 ? x / r : 0.0, ey = r > 0 ? y / r : 1.0;
  const double s = std::sin(theta);
  return {ex * s, ey * s, -std::cos(theta)};
}
// The angle of `d` (unit) from the view axis, and its azimuth's unit vector on the film.
inline double off_axis_angle(Vec3d d) {
  return std::acos(std::fmax(-1.0, std::fmin(1.0, -d.z)));
}
inline Vec2d film_azimuth(Vec3d d) {
  const double r = std::hypot(d.x, d.y);
  return r > 0 ? Vec2d{d.x / r, d.y / r} : Vec2d{0.0, 1.0};
}

// Equidistant: theta = r fov / 2 with r = 1 on the circle inscribed in the film square (an
// ellipse on a non-square image, as Cycles renders it).
inline Vec3d equidistant_direction(Film f, double fov_rad) {
  const double x = 2 * (f.u - 0.5), y = 2 * (f.v - 0.5);
  const double r = std::hypot(x, y);
  if (!(r <= 1)) return {};
  return fisheye_direction(r * fov_rad / 2, x, y);
}
inline Film equidistant_film(Vec3d d, double fov_rad) {
  const double r = off_axis_angle(d) / (fov_rad / 2);
  const Vec2d e = film_azimuth(d);
  return {0.5 + r * e.x / 2, 0.5 + r * e.y / 2};
}

// Equisolid: r = 2 f sin(theta / 2) in mm on the imaged sensor, cut at theta = fov / 2.
inline Vec3d equisolid_direction(Film f, double lens_mm, double fov_rad, Vec2d sensor_mm) {
  const double x = (f.u - 0.5) * sensor_mm.x, y = (f.v - 0.5) * sensor_mm.y;
  const double r = std::hypot(x, y);
  if (!(r <= 2 * lens_mm * std::sin(fov_rad / 4))) return {};
  return fisheye_direction(2 * std::asin(std::fmin(1.0, r / (2 * lens_mm))), x, y);
}
inline Film equisolid_film(Vec3d d, double lens_mm, Vec2d sensor_mm) {
  const double r = 2 * lens_mm * std::sin(off_axis_angle(d) / 2);
  const Vec2d e = film_azimuth(d);
  return {0.5 + r * e.x / sensor_mm.x, 0.5 + r * e.y / sensor_mm.y};
}

// Polynomial (Blender's "Fisheye Lens Polynomial", fitted to a real lens by its calibration):
// theta(r) = -(k0 + k1 r + k2 r^2 + k3 r^3 + k4 r^4), r in mm on the imaged sensor. Cycles cuts
// at |theta| > fov / 2; filmback also cuts where the mapping folds over (dtheta/dr changes sign,
// so two radii would image one direction): such pixels are black, where Cycles would repeat the
// image (docs/camera-model.md).
struct Polynomial {
  double k[5];
  double theta(double r_mm) const {
    return -(k[0] + r_mm * (k[1] + r_mm * (k[2] + r_mm * (k[3] + r_mm * k[4]))));
  }
  double slope(double r_mm) const {
    return -(k[1] + r_mm * (2 * k[2] + r_mm * (3 * k[3] + r_mm * 4 * k[4])));
  }
  // The first radius in (0, r_max_mm] where theta stops being monotonic, else r_max_mm. A fixed
  // scan (4096 steps) then bisection: bounded work for any coefficients.
  double fold_radius_mm(double r_max_mm) const {
    constexpr int kSteps = 4096;
    const double sign = slope(0) != 0 ? slope(0) : slope(r_max_mm / kSteps);
    double previous = 0;
    for (int i = 1; i <= kSteps; ++i) {
      const double r = r_max_mm * i / kSteps;
      if (slope(r) * sign > 0) {
        previous = r;
        continue;
      }
      double lo = previous, hi = r;
      for (int j = 0; j < 60; ++j) {
        const double mid = (lo + hi) / 2;
        (slope(mid) * sign > 0 ? lo : hi) = mid;
      }
      return lo;
    }
    return r_max_mm;
  }
};

// `fold_mm`: Polynomial::fold_radius_mm over the image's corner radius.
inline Vec3d polynomial_direction(Film f, const Polynomial& p, double fov_rad, double fold_mm,
                                  Vec2d sensor_mm) {
  const double x = (f.u - 0.5) * sensor_mm.x, y = (f.v - 0.5) * sensor_mm.y;
  const double r = std::hypot(x, y);
  const double theta = p.theta(r);
  if (!(r <= fold_mm && std::abs(theta) <= fov_rad / 2)) return {};
  return fisheye_direction(theta, x, y);
}
// The inverse on the monotonic part [0, fold_mm], by bisection (theta may decrease with r, as it
// does for negative k1: the image is then turned half a turn, as in Cycles). The direction's
// azimuth is flipped when theta is negative there.
inline Film polynomial_film(Vec3d d, const Polynomial& p, double fold_mm, Vec2d sensor_mm) {
  const double increasing = p.theta(fold_mm) >= p.theta(0) ? 1.0 : -1.0;
  const double target = off_axis_angle(d);
  double lo = 0, hi = fold_mm;
  for (int j = 0; j < 80; ++j) {
    const double mid = (lo + hi) / 2;
    (p.theta(mid) * increasing < target ? lo : hi) = mid;
  }
  const double r = (lo + hi) / 2;
  const Vec2d e = film_azimuth(d);
  return {0.5 + increasing * r * e.x / sensor_mm.x, 0.5 + increasing * r * e.y / sensor_mm.y};
}

// ------------------------------------------------------------------ the others

// Mirror ball: the film square is an orthographic view of a unit mirrored sphere seen from behind
// the camera; a point (x, y) on its disc, of normal n = (x, y, w) with w = sqrt(1 - x^2 - y^2),
// reflects the view ray +Z into 2 w n - Z (Cycles' mirrorball_to_direction).
inline Vec3d mirrorball_direction(Film f) {
  const double x = 2 * f.u - 1, y = 2 * f.v - 1;
  const double w2 = 1 - x * x - y * y;
  if (!(w2 >= 0)) return {};
  const double w = std::sqrt(w2);
  return {2 * w * x, 2 * w * y, 1 - 2 * w2};
}
// The normal halfway between the reflected direction and +Z.
inline Film mirrorball_film(Vec3d d) {
  const double scale = 2 * std::sqrt(std::fmax(0.0, (1 - d.z) / 2));
  const double x = scale > 0 ? d.x / scale : d.x, y = scale > 0 ? d.y / scale : d.y;
  return {(x + 1) / 2, (y + 1) / 2};
}

// Equirectangular: longitude (rightwards from the view axis) and latitude (upwards) linear in u
// and v over Blender's ranges.
struct AngleRange {
  double min, max;
  double at(double t) const { return min + (max - min) * t; }
  double fraction(double x) const { return (x - min) / (max - min); }
};
inline Vec3d equirectangular_direction(Film f, AngleRange longitude, AngleRange latitude) {
  const double lon = longitude.at(f.u), lat = latitude.at(f.v);
  return {std::cos(lat) * std::sin(lon), std::sin(lat), -std::cos(lat) * std::cos(lon)};
}
inline Film equirectangular_film(Vec3d d, AngleRange longitude, AngleRange latitude) {
  return {longitude.fraction(std::atan2(d.x, -d.z)),
          latitude.fraction(std::asin(std::fmax(-1.0, std::fmin(1.0, d.y))))};
}

// Central cylindrical (Blender 4.0): a unit cylinder around the vertical axis, longitude linear
// in u and height (divided by the cylinder's radius) linear in v; rays through the cylinder from
// its centre (Cycles 4.x central_cylindrical_to_direction).
inline Vec3d central_cylindrical_direction(Film f, AngleRange longitude, AngleRange height) {
  const double lon = longitude.at(f.u), h = height.at(f.v);
  return normalize(Vec3d{std::sin(lon), h, -std::cos(lon)});
}
inline Film central_cylindrical_film(Vec3d d, AngleRange longitude, AngleRange height) {
  return {longitude.fraction(std::atan2(d.x, -d.z)), height.fraction(d.y / std::hypot(d.x, d.z))};
}

// One face of an equiangular cubemap (Blender 4.0; Google's EAC, "Bringing pixels front and
// center in VR video", 2017): the angle, not the tangent, is linear across the 90 degree face.
inline Vec3d cubemap_face_direction(Film f) {
  return normalize(Vec3d{std::tan((f.u - 0.5) * kPi / 2), std::tan((f.v - 0.5) * kPi / 2), -1.0});
}
inline Film cubemap_face_film(Vec3d d) {
  return {0.5 + std::atan2(d.x, -d.z) * 2 / kPi, 0.5 + std::atan2(d.y, -d.z) * 2 / kPi};
}

// ------------------------------------------------------------------ what `filmback info` prints

// printf into a std::string, for a plugin's describe() lines.
template <typename... Args>
std::string text(const char* format, Args... args) {
  char line[256];
  std::snprintf(line, sizeof line, format, args...);
  return line;
}
inline double degrees(double rad) {
  return rad * 180 / kPi;
}

// A fisheye's field of view across the frame's width, height and diagonal: twice the angle
// `theta_deg(r)` at the half side, r in the units `half_sides` are in.
template <typename Theta>
std::string fisheye_fov_text(Vec2d half_sides, Theta theta_deg) {
  return text("field of view: %.6g deg horizontal x %.6g deg vertical, %.6g deg diagonal\n",
              2 * theta_deg(half_sides.x), 2 * theta_deg(half_sides.y),
              2 * theta_deg(std::hypot(half_sides.x, half_sides.y)));
}

// The focal length a lens of `focal_mm` on the imaged sensor would have on 35 mm film for the same
// diagonal angle (43.27 mm diagonal), as `filmback info` gives a perspective camera's.
inline double equivalent_35mm_mm(double focal_mm, Vec2d sensor_mm) {
  return focal_mm * 43.27 / std::hypot(sensor_mm.x, sensor_mm.y);
}

// ------------------------------------------------------------------ the camera plugins' frame
//
// Cycles traces panoramas with depth of field when the shot has an aperture
// (kernel/camera/camera.h, camera_sample_panorama): every panorama plugin declares Blender's lens
// values first in its schema, as thinlens names them, then its own.
inline constexpr fb_param_desc kLensParams[] = {
    {"fstop", FB_PARAM_FLOAT, "inf", "f-number", nullptr, 1e-6, HUGE_VAL,
     "aperture as an f-number N: radius f / 2N with f the shot's focal length; inf: a pinhole"},
    {"focus_distance_m", FB_PARAM_FLOAT, "inf", "m", nullptr, 1e-6, HUGE_VAL,
     "distance of the sphere in focus along each ray; inf: focused at infinity"},
    FB_APERTURE_SHAPE_PARAMS,
};
constexpr size_t kLensParamCount = std::size(kLensParams);

// A plugin's schema: the lens values, then its own (`with_lens(kOwn).params` for fb::describe).
template <size_t N>
struct Schema {
  fb_param_desc params[kLensParamCount + N];
};
template <size_t N>
constexpr Schema<N> with_lens(const fb_param_desc (&own)[N]) {
  Schema<N> schema{};
  for (size_t i = 0; i < kLensParamCount; ++i)
    schema.params[i] = kLensParams[i];
  for (size_t i = 0; i < N; ++i)
    schema.params[kLensParamCount + i] = own[i];
  return schema;
}
constexpr Schema<0> with_lens() {
  Schema<0> schema{};
  for (size_t i = 0; i < kLensParamCount; ++i)
    schema.params[i] = kLensParams[i];
  return schema;
}

// Cycles' aperture frame around a ray direction d: U is its panorama space's +X axis made
// perpendicular to d, V = d x U. +X is filmback's -Z, but the mirror ball's +X, through its
// reflected space (x, z, y), is filmback's +X and the frame's handedness flips.
struct LensFrame {
  Vec3d u, v;
};
inline LensFrame lens_frame(Vec3d d, bool mirror_ball) {
  const Vec3d axis = mirror_ball ? Vec3d{1, 0, 0} : Vec3d{0, 0, -1};
  Vec3d u = axis - d * dot(axis, d);
  // Along the axis Cycles' frame is 0/0; any perpendicular one serves a round aperture alike.
  if (!(dot(u, u) > 1e-18)) u = mirror_ball ? Vec3d{0, 0, 1} : Vec3d{1, 0, 0};
  u = normalize(u);
  const Vec3d v = cross(d, u);
  return {u, mirror_ball ? -v : v};
}

// The projection is the plugin's own: a shot of any projection renders through it (a perspective
// Blender shot with `--camera-model equirectangular`), its sensor, shift and clip range as usual.
//
// A panorama plugin is a Mapping: constructed from its parameter values and the setup (throwing
// std::invalid_argument naming a parameter when they cannot make an image), with
// `Vec3d direction(Film) const` and `std::string describe() const` (its field of view, lines for
// `filmback info`); a mirror ball also has `static constexpr bool kMirrorBall`.
// Rays are clipped along the ray between clip_near_m and clip_far_m, as Cycles clips panoramas
// (camera_sample_to_ray); a raster point with no direction gets weight 0. With an aperture (of
// radius f / 2N, f the shot's focal length, as Blender sets Cycles' aperturesize for every camera
// type), a ray leaves the lens point l = U lx + V ly and passes through the point at the focus
// distance along the pinhole ray: Cycles focuses panoramas on a sphere, not a plane.
template <typename Mapping>
class Camera {
 public:
  Camera(const fb_value* values, const fb_camera_setup& s)
      : setup_(s),
        near_(s.clip_near_m),
        far_(s.clip_far_m),
        focus_m_(kFocus(values)),
        blades_(uint32_t(kBlades(values))),
        rotation_(float(kRotation(values))),
        inverse_ratio_(float(1 / kRatio(values))),
        mapping_(values, s) {
    if (s.sensor_model != FB_SENSOR_SIMPLE)
      throw std::invalid_argument("the physical sensor is not modelled for panoramic cameras");
    if (!(s.image_width_px > 0 && s.image_height_px > 0) || !(near_ >= 0) || !(far_ > near_))
      throw std::invalid_argument("the image must have pixels and the clip range be non-empty");
    if (!(std::abs(s.shift_x) <= 1e3 && std::abs(s.shift_y) <= 1e3))
      throw std::invalid_argument("the lens shift is not finite or too large");
    if (blades_ == 1 || blades_ == 2)
      throw std::invalid_argument("an aperture has 0 (round) or at least 3 blades");
    if (const double fstop = kFstop(values); !std::isinf(fstop)) {
      if (!(s.focal_length_mm > 0 && s.focal_length_mm < 1e6))
        throw std::invalid_argument("an aperture needs the shot's focal length (f / 2N)");
      radius_m_ = s.focal_length_mm * 1e-3 / (2 * fstop);
    }
  }

  uint32_t needs() const { return radius_m_ > 0 ? FB_CAMERA_NEEDS_LENS : 0; }

  // The mapping's field of view and what it derives, then the aperture, for `filmback info`.
  std::string describe() const {
    std::string lines = mapping_.describe();
    if (radius_m_ > 0)
      lines += text(
          "aperture diameter: %.6g mm (f/%.6g of the %.6g mm lens), focused %s\n", 2e3 * radius_m_,
          setup_.focal_length_mm / (2e3 * radius_m_), setup_.focal_length_mm,
          std::isinf(focus_m_) ? "at infinity" : text("%.6g m along each ray", focus_m_).c_str());
    return lines;
  }

  void generate(const fb_camera_sample& sample, fb_camera_ray& ray) const {
    const Vec3d d = mapping_.direction(film_from_raster(setup_, sample.film_x, sample.film_y));
    const double length = std::sqrt(dot(d, d));
    const bool none = !(length > 0 && std::isfinite(length));
    Vec3d origin{}, direction = none ? Vec3d{0, 0, -1} : d / length;
    if (radius_m_ > 0 && !none) {
      const Vec2f l =
          sample_aperture({sample.lens_u, sample.lens_v}, blades_, rotation_, inverse_ratio_);
      const LensFrame frame = lens_frame(direction, is_mirror_ball());
      origin = (frame.u * double(l.x) + frame.v * double(l.y)) * radius_m_;
      if (!std::isinf(focus_m_)) direction = normalize(direction * focus_m_ - origin);
    }
    Vec3f(origin).store(ray.origin);
    Vec3f(direction).store(ray.direction);
    ray.t_min = float(near_);
    ray.t_max = float(far_);
    ray.weight = none ? 0.f : 1.f;
  }

 private:
  static constexpr bool is_mirror_ball() {
    if constexpr (requires { Mapping::kMirrorBall; })
      return Mapping::kMirrorBall;
    else
      return false;
  }
  static constexpr auto kFstop = fb::param<double>(kLensParams, "fstop");
  static constexpr auto kFocus = fb::param<double>(kLensParams, "focus_distance_m");
  static constexpr auto kBlades = fb::param<int>(kLensParams, "aperture_blades");
  static constexpr auto kRotation = fb::param<double>(kLensParams, "aperture_rotation_rad");
  static constexpr auto kRatio = fb::param<double>(kLensParams, "aperture_ratio");

  fb_camera_setup setup_;
  double near_, far_;
  double radius_m_ = 0, focus_m_;
  uint32_t blades_;
  float rotation_, inverse_ratio_;
  Mapping mapping_;
};

}  // namespace fb::panorama
