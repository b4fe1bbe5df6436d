// Lens distortion of a tracked plate: Blender's motion-tracking camera models (libmv, Blender 3.4:
// polynomial, divisions, Nuke, Brown), applied in the camera so that CG lands on the plate's
// pixels without resampling. The models and their units are in docs/camera-model.md, "Lens
// distortion"; the equations follow libmv's intern/libmv/libmv/simple_pipeline/
// distortion_models.h (read, not copied).
//
// A camera plugin asks, for a film position of the distorted image, where the undistorted
// (pinhole) image has that point: the inverse of the model's undistorted -> distorted map, solved
// by a bounded Newton iteration (libmv solves it by Levenberg-Marquardt). A position whose inverse
// does not exist (beyond the fold of the model's radial function, or no convergence) has none:
// the camera gives it weight 0, black, never NaN.
//
// Frames, as Blender's Movie Distortion node uses them (compositor MovieDistortionOperation): the
// clip's pixel frame has its origin at the bottom-left, pixel (i, j)'s centre at (i, j); the
// render's pixels map to the clip's by the ratio of the sizes; y is divided by the clip's pixel
// aspect; focal length and principal point are the clip's, in its pixels.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "plugin_abi.h"
#include "plugin_sdk.h"
#include "vec.h"

namespace fb {

enum class DistortionModel { kNone, kPolynomial, kDivision, kNuke, kBrown };

// The coefficients of every model (at most one model's may be non-zero) and the clip's camera.
struct LensDistortionParams {
  std::array<double, 3> polynomial_k{};  // Blender's K1, K2, K3
  std::array<double, 2> division_k{};
  std::array<double, 2> nuke_k{};
  std::array<double, 4> brown_k{};
  std::array<double, 2> brown_p{};
  double clip_width_px = 0, clip_height_px = 0;
  double focal_length_px = 0;
  Vec2d principal_px{};  // Blender 3.4's "Optical Center", from the clip's bottom-left corner
  double pixel_aspect = 1;
};

// The parameters every projective camera plugin declares, in Blender's Track > Camera units
// (put FB_LENS_DISTORTION_PARAMS at the end of a plugin's schema; read it with
// lens_distortion_params). A model is chosen by giving its coefficients: those of two models
// at once are refused.
// clang-format off
#define FB_LENS_DISTORTION_PARAMS                                                                \
  {"polynomial_k1", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "polynomial model's K1"},       \
  {"polynomial_k2", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "polynomial model's K2"},       \
  {"polynomial_k3", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "polynomial model's K3"},       \
  {"division_k1", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "divisions model's K1"},          \
  {"division_k2", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "divisions model's K2"},          \
  {"nuke_k1", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "Nuke model's K1"},                   \
  {"nuke_k2", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "Nuke model's K2"},                   \
  {"brown_k1", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "Brown model's K1"},                 \
  {"brown_k2", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "Brown model's K2"},                 \
  {"brown_k3", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "Brown model's K3"},                 \
  {"brown_k4", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "Brown model's K4"},                 \
  {"brown_p1", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "Brown model's P1 (tangential)"},    \
  {"brown_p2", FB_PARAM_FLOAT, "0", "", nullptr, -1e6, 1e6, "Brown model's P2 (tangential)"},    \
  {"clip_width_px", FB_PARAM_FLOAT, "0", "px", nullptr, 0, 1e6,                                  \
   "width of the tracked clip (needed with a distortion)"},                                      \
  {"clip_height_px", FB_PARAM_FLOAT, "0", "px", nullptr, 0, 1e6,                                 \
   "height of the tracked clip (needed with a distortion)"},                                     \
  {"clip_focal_length_px", FB_PARAM_FLOAT, "0", "px", nullptr, 0, 1e9,                           \
   "the solved focal length in the clip's pixels (needed with a distortion)"},                   \
  {"clip_principal_x_px", FB_PARAM_FLOAT, "0", "px", nullptr, -1e7, 1e7,                         \
   "optical centre from the clip's left edge"},                                                  \
  {"clip_principal_y_px", FB_PARAM_FLOAT, "0", "px", nullptr, -1e7, 1e7,                         \
   "optical centre from the clip's bottom edge"},                                                \
  {"clip_pixel_aspect", FB_PARAM_FLOAT, "1", "", nullptr, 1e-3, 1e3,                             \
   "pixel aspect ratio of the clip (width / height)"}
// clang-format on

namespace distortion_detail {

// Newton's iteration on a 2D map: at most this many steps, converged when the residual is below
// this (normalized units, where 1 is one focal length: 1e-13 is ~1e-10 px at f = 1000 px).
constexpr int kMaxNewtonSteps = 50;
constexpr double kNewtonTolerance = 1e-13;
// Normalized radii beyond this (a field of view within 0.01 degree of 180) are not traced.
constexpr double kMaxRadius = 1e4;

struct Jacobian {
  double xx, xy, yx, yy;
  double det() const { return xx * yy - xy * yx; }
};

// Brown-Conrady radial and tangential distortion of a normalized point (libmv's
// ApplyBrownDistortionModel; the polynomial model is this with k4 = p1 = p2 = 0):
// x_d = x (1 + k1 r^2 + k2 r^4 + k3 r^6 + k4 r^8) + p1 (r^2 + 2 x^2) + 2 p2 x y, likewise y with
// p1 and p2 swapped.
struct Radial {
  std::array<double, 4> k{};
  std::array<double, 2> p{};
  Vec2d apply(Vec2d n, Jacobian* jacobian = nullptr) const {
    const double x = n.x, y = n.y, r2 = x * x + y * y;
    const double scale = 1 + r2 * (k[0] + r2 * (k[1] + r2 * (k[2] + r2 * k[3])));
    const double scale_d_r2 = k[0] + r2 * (2 * k[1] + r2 * (3 * k[2] + r2 * 4 * k[3]));
    if (jacobian)
      *jacobian = {scale + 2 * x * x * scale_d_r2 + 6 * p[0] * x + 2 * p[1] * y,
                   2 * x * y * scale_d_r2 + 2 * p[0] * y + 2 * p[1] * x,
                   2 * x * y * scale_d_r2 + 2 * p[1] * x + 2 * p[0] * y,
                   scale + 2 * y * y * scale_d_r2 + 6 * p[1] * y + 2 * p[0] * x};
    return {x * scale + p[0] * (r2 + 2 * x * x) + 2 * p[1] * x * y,
            y * scale + p[1] * (r2 + 2 * y * y) + 2 * p[0] * x * y};
  }
  // d(r scale(r)) / dr over r = 1 + 3 k1 r^2 + 5 k2 r^4 + 7 k3 r^6 + 9 k4 r^8: where it reaches
  // 0 the radial map folds over.
  double radial_slope(double r) const {
    const double r2 = r * r;
    return 1 + r2 * (3 * k[0] + r2 * (5 * k[1] + r2 * (7 * k[2] + r2 * 9 * k[3])));
  }
};

// The division map p / (1 + k1 r^2 + k2 r^4): libmv's divisions model (undistorted ->
// distorted) and Nuke's (distorted -> undistorted, in its own normalization).
struct Division {
  std::array<double, 2> k{};
  Vec2d apply(Vec2d n, Jacobian* jacobian = nullptr) const {
    const double r2 = n.x * n.x + n.y * n.y;
    const double d = 1 + r2 * (k[0] + r2 * k[1]);
    const double d_r2 = k[0] + 2 * r2 * k[1];
    if (jacobian) {
      // d(x/d)/dx = 1/d - x * 2x d_r2 / d^2
      const double g = 2 * d_r2 / (d * d);
      *jacobian = {1 / d - n.x * n.x * g, -n.x * n.y * g, -n.x * n.y * g, 1 / d - n.y * n.y * g};
    }
    return {n.x / d, n.y / d};
  }
  // The radial map r / d(r) rises while d > 0 and its slope (1 - k1 r^2 - 3 k2 r^4) / d^2 is
  // positive: a negative here is a fold or a pole.
  double radial_slope(double r) const {
    const double r2 = r * r;
    const double d = 1 + r2 * (k[0] + r2 * k[1]);
    return d > 0 ? 1 - r2 * (k[0] + 3 * r2 * k[1]) : -1;
  }
};

// The radius up to which a radial map rises from 0 (its slope stays positive): the domain on
// which it is invertible. Geometric scan, then bisection; kMaxRadius when it never folds.
template <typename Map>
double rising_radius(const Map& map) {
  double inside = 0;
  for (double r = 1e-3; r <= kMaxRadius; r *= 1.05) {
    if (!(map.radial_slope(r) > 0)) {
      double outside = r;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (inside + outside);
        (map.radial_slope(mid) > 0 ? inside : outside) = mid;
      }
      return inside;
    }
    inside = r;
  }
  return kMaxRadius;
}

// The point n with map(n) = target inside radius `domain`, by Newton's iteration from `guess`;
// none when it does not converge, leaves the domain, or lands where the map folds (det J <= 0).
template <typename Map>
std::optional<Vec2d> solve(const Map& map, Vec2d target, Vec2d guess, double domain) {
  Vec2d n = guess;
  for (int step = 0; step < kMaxNewtonSteps; ++step) {
    Jacobian j;
    const Vec2d value = map.apply(n, &j);
    const double ex = value.x - target.x, ey = value.y - target.y;
    const double det = j.det();
    if (!(det > 0) || !std::isfinite(ex) || !std::isfinite(ey)) return std::nullopt;
    if (std::hypot(ex, ey) <= kNewtonTolerance * (1 + std::hypot(target.x, target.y)))
      return std::hypot(n.x, n.y) < domain ? std::optional<Vec2d>(n) : std::nullopt;
    n = {n.x - (j.yy * ex - j.xy * ey) / det, n.y - (j.xx * ey - j.yx * ex) / det};
    if (!(std::hypot(n.x, n.y) < domain)) return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace distortion_detail

// One model, in the clip's pixel frame (libmv's image coordinates).
class LensDistortion {
 public:
  // Throws std::invalid_argument (a plugin's create() reports it) when two models are given, or a
  // model without the clip's focal length.
  explicit LensDistortion(const LensDistortionParams& p) : p_(p) {
    const auto any = [](const auto& k) {
      return std::any_of(k.begin(), k.end(), [](double x) { return x != 0; });
    };
    const bool brown = any(p.brown_k) || any(p.brown_p);
    const int models = int(any(p.polynomial_k)) + any(p.division_k) + any(p.nuke_k) + brown;
    if (models > 1)
      throw std::invalid_argument(
          "the coefficients of more than one distortion model are given (polynomial_*, "
          "division_*, nuke_*, brown_*): give one model's");
    model_ = any(p.polynomial_k) ? DistortionModel::kPolynomial
             : any(p.division_k) ? DistortionModel::kDivision
             : any(p.nuke_k)     ? DistortionModel::kNuke
             : brown             ? DistortionModel::kBrown
                                 : DistortionModel::kNone;
    if (model_ == DistortionModel::kNone) return;
    if (!(p.focal_length_px > 0 && p.clip_width_px >= 1 && p.clip_height_px >= 1))
      throw std::invalid_argument(
          "a lens distortion needs the clip's focal length and size (clip_focal_length_px, "
          "clip_width_px, clip_height_px)");
    radial_.k = {p.polynomial_k[0], p.polynomial_k[1], p.polynomial_k[2], 0};
    if (model_ == DistortionModel::kBrown) {
      radial_.k = p.brown_k;
      radial_.p = p.brown_p;
    }
    division_.k = model_ == DistortionModel::kNuke ? p.nuke_k : p.division_k;
    domain_ = model_ == DistortionModel::kDivision || model_ == DistortionModel::kNuke
                  ? distortion_detail::rising_radius(division_)
                  : distortion_detail::rising_radius(radial_);
    // Blender hands libmv the principal point's y and the image height divided by the pixel
    // aspect (tracking_cameraIntrinscisOptionsFromTracking); Nuke normalizes by half the larger
    // side of that image (libmv's InvertNukeDistortionModel).
    principal_ = {p.principal_px.x, p.principal_px.y / p.pixel_aspect};
    unit_px_ = model_ == DistortionModel::kNuke
                   ? 0.5 * std::max(p.clip_width_px, std::floor(p.clip_height_px / p.pixel_aspect))
                   : p.focal_length_px;
  }

  DistortionModel model() const { return model_; }
  bool identity() const { return model_ == DistortionModel::kNone; }

  // The undistorted image position of a distorted one, both in the clip's pixels (y already
  // divided by the pixel aspect, as libmv sees them); none where the model has no inverse.
  std::optional<Vec2d> undistort(Vec2d distorted) const {
    if (identity()) return distorted;
    // Nuke's model maps distorted to undistorted in closed form; the others the other way.
    return in_model_units(distorted, /*solve=*/model_ != DistortionModel::kNuke);
  }

  // The distorted image position of an undistorted one (the model's own direction; Nuke's by
  // Newton), for tests and tools; none where the model folds.
  std::optional<Vec2d> distort(Vec2d undistorted) const {
    if (identity()) return undistorted;
    return in_model_units(undistorted, /*solve=*/model_ == DistortionModel::kNuke);
  }

  // The render's raster position (x right, y down, origin top-left, continuous) whose pinhole ray
  // lands where the distorted raster position `film` shows, for a render of width x height px;
  // none where the model has no inverse. The clip's frame is the compositor's: pixel centres at
  // integers, y up, scaled by clip / render size, y over the pixel aspect.
  std::optional<Vec2d> undistorted_film(Vec2d film, double width_px, double height_px) const {
    if (identity()) return film;
    const double sx = width_px / p_.clip_width_px, sy = height_px / p_.clip_height_px;
    const Vec2d clip = {(film.x - 0.5) / sx, (height_px - film.y - 0.5) / sy / p_.pixel_aspect};
    const std::optional<Vec2d> u = undistort(clip);
    if (!u) return std::nullopt;
    return Vec2d{u->x * sx + 0.5, height_px - u->y * sy * p_.pixel_aspect - 0.5};
  }

 private:
  // The model's closed-form map (or, with `solve`, its inverse by Newton's iteration) of an image
  // position, in the model's units about the optical centre: focal lengths, or for Nuke half the
  // image's larger side (libmv's InvertNukeDistortionModel).
  std::optional<Vec2d> in_model_units(Vec2d image, bool solve) const {
    const Vec2d p = {(image.x - principal_.x) / unit_px_, (image.y - principal_.y) / unit_px_};
    const bool radial = model_ == DistortionModel::kPolynomial || model_ == DistortionModel::kBrown;
    std::optional<Vec2d> q;
    if (solve)
      q = radial ? distortion_detail::solve(radial_, p, p, domain_)
                 : distortion_detail::solve(division_, p, p, domain_);
    else if (std::hypot(p.x, p.y) < domain_)
      q = radial ? radial_.apply(p) : division_.apply(p);
    if (!q) return std::nullopt;
    return Vec2d{principal_.x + q->x * unit_px_, principal_.y + q->y * unit_px_};
  }

  LensDistortionParams p_;
  DistortionModel model_ = DistortionModel::kNone;
  distortion_detail::Radial radial_;
  distortion_detail::Division division_;
  double domain_ = distortion_detail::kMaxRadius;
  Vec2d principal_{};
  double unit_px_ = 1;  // the model's unit of length in the clip's pixels
};

// The distortion parameters of a schema holding FB_LENS_DISTORTION_PARAMS, from create()'s
// values.
template <size_t N>
LensDistortionParams lens_distortion_params(const fb_param_desc (&schema)[N],
                                            const fb_value* values) {
  const auto get = [&](const char* name) { return param<double>(schema, name)(values); };
  LensDistortionParams p;
  p.polynomial_k = {get("polynomial_k1"), get("polynomial_k2"), get("polynomial_k3")};
  p.division_k = {get("division_k1"), get("division_k2")};
  p.nuke_k = {get("nuke_k1"), get("nuke_k2")};
  p.brown_k = {get("brown_k1"), get("brown_k2"), get("brown_k3"), get("brown_k4")};
  p.brown_p = {get("brown_p1"), get("brown_p2")};
  p.clip_width_px = get("clip_width_px");
  p.clip_height_px = get("clip_height_px");
  p.focal_length_px = get("clip_focal_length_px");
  p.principal_px = {get("clip_principal_x_px"), get("clip_principal_y_px")};
  p.pixel_aspect = get("clip_pixel_aspect");
  return p;
}

}  // namespace fb
