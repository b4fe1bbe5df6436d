// What POV-Ray 3.7's non-perspective cameras share (the pov_* camera plugins; docs/camera-model.md,
// "POV-Ray's projections"): its image coordinates, its camera frame and its "no ray".
//
// POV-Ray builds a primary ray from the raster point (x, y) of a W x H image, y down, as
// x0 = x / W - 1/2 (right) and y0 = 1/2 - y / H (up), both in [-1/2, 1/2] (tracepixel.cpp
// TracePixel::CreateCameraRay), and a direction a R^ + b U^ + c D^ from the camera's right, up and
// direction vectors, normalised (or, for some types, as they are: their lengths are then
// parameters). The importer poses filmback's camera with R^, U^, D^ as its x, y and -z axes
// (importers/pov/pov_camera.cpp), so (a, b, c) is the camera-space direction (a, b, -c).
//
// A raster point POV-Ray traces no ray for (outside a fisheye's circle) gets weight 0: black, as
// POV-Ray leaves it, with a finite direction all the same.
#pragma once

#include <filmback/plugin_sdk.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace fb::pov_projection {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;

// The parameters several types share. The angle is POV-Ray's `angle`, in the degrees its users
// type, unbounded there but for its sign; the bound here keeps sines meaningful. Lengths are of
// the camera's vectors after POV-Ray's camera rules (look_at, transforms): POV-Ray units, which
// the importer takes as metres.
constexpr double kMaxAngleDeg = 1e6;
constexpr fb_param_desc kAngleParam = {
    "angle_deg",
    FB_PARAM_FLOAT,
    "90",
    "deg",
    nullptr,
    0,
    kMaxAngleDeg,
    "POV-Ray's camera angle (its default 90), the field of view as this type spreads it"};
constexpr fb_param_desc kRightLengthParam = {
    "right_length_m", FB_PARAM_FLOAT, "1.33", "m",
    nullptr,          1e-12,          1e12,   "length of POV-Ray's right vector"};
constexpr fb_param_desc kUpLengthParam = {
    "up_length_m", FB_PARAM_FLOAT, "1", "m", nullptr, 1e-12, 1e12, "length of POV-Ray's up vector"};

// The schema of the types that take an angle and both lengths (fisheye, ultra_wide_angle), and
// its values.
constexpr fb_param_desc kAngleAndLengthsParams[] = {kAngleParam, kRightLengthParam, kUpLengthParam};
struct AngleAndLengths {
  double angle_rad, right_m, up_m;
};
inline AngleAndLengths angle_and_lengths(const fb_value* values) {
  constexpr auto angle = fb::param<double>(kAngleAndLengthsParams, "angle_deg");
  constexpr auto right = fb::param<double>(kAngleAndLengthsParams, "right_length_m");
  constexpr auto up = fb::param<double>(kAngleAndLengthsParams, "up_length_m");
  return {angle(values) * kRadiansPerDegree, right(values), up(values)};
}

// POV-Ray's image coordinates of a raster point.
struct ImagePoint {
  double x0, y0;  // right and up, in [-1/2, 1/2]
};

// The setup every POV-Ray projection needs, checked once.
class PovImage {
 public:
  explicit PovImage(const fb_camera_setup& s)
      : width_px_(double(s.image_width_px)),
        height_px_(double(s.image_height_px)),
        near_m_(s.clip_near_m),
        far_m_(s.clip_far_m) {
    if (s.projection != FB_PROJECTION_PANORAMIC)
      throw std::invalid_argument(
          "POV-Ray's camera types are panoramic projections: the shot's camera is not one");
    if (s.sensor_model == FB_SENSOR_PHYSICAL)
      throw std::invalid_argument(
          "the physical sensor needs an aperture to expose through; POV-Ray's camera types have "
          "none here");
    if (!(width_px_ > 0) || !(height_px_ > 0)) throw std::invalid_argument("the image is empty");
    if (!(near_m_ >= 0) || !(far_m_ > near_m_))
      throw std::invalid_argument("the clip range is empty");
  }

  ImagePoint point(const fb_camera_sample& s) const {
    return {s.film_x / width_px_ - 0.5, 0.5 - s.film_y / height_px_};
  }

  // The ray along a R^ + b U^ + c D^ (not all zero) from the camera origin moved by
  // (origin_right, origin_up) metres along R^ and U^; clipped by distance along the ray, as a
  // panorama has no view axis to clip by depth along.
  void set_ray(double a, double b, double c, fb_camera_ray& ray, double origin_right_m = 0,
               double origin_up_m = 0) const {
    const double inverse_length = 1 / std::sqrt(a * a + b * b + c * c);
    ray.origin[0] = float(origin_right_m);
    ray.origin[1] = float(origin_up_m);
    ray.origin[2] = 0.f;
    ray.direction[0] = float(a * inverse_length);
    ray.direction[1] = float(b * inverse_length);
    ray.direction[2] = float(-c * inverse_length);
    ray.t_min = float(near_m_);
    ray.t_max = float(far_m_);
    ray.weight = 1.f;
  }

  // No ray: weight 0 (black), along the view so that nothing downstream meets a NaN.
  static void set_no_ray(fb_camera_ray& ray) {
    ray.origin[0] = ray.origin[1] = ray.origin[2] = 0.f;
    ray.direction[0] = ray.direction[1] = 0.f;
    ray.direction[2] = -1.f;
    ray.t_min = 0.f;
    ray.t_max = 0.f;
    ray.weight = 0.f;
  }

  double width_px() const { return width_px_; }
  double height_px() const { return height_px_; }

 private:
  double width_px_, height_px_, near_m_, far_m_;
};

// printf into a string: the plugins' describe() lines for `filmback info`.
template <typename... Args>
std::string text_of(const char* format, Args... args) {
  char text[256];
  std::snprintf(text, sizeof text, format, args...);
  return text;
}

// The ray at polar angle theta from D^ in the image direction (u, v), r = |(u, v)| > 0 (or any
// direction when theta is 0): fisheye and omnimax. POV-Ray takes the image angle phi as asin(v/r)
// or pi - asin(v/r) by the sign of u, so cos(phi) = u/r and sin(phi) = v/r.
inline void set_polar_ray(const PovImage& image, double u, double v, double r, double theta,
                          fb_camera_ray& ray) {
  const double cos_phi = r > 0 ? u / r : 1, sin_phi = r > 0 ? v / r : 0;
  const double sin_theta = std::sin(theta);
  image.set_ray(cos_phi * sin_theta, sin_phi * sin_theta, std::cos(theta), ray);
}

}  // namespace fb::pov_projection
