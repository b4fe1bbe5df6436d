// Camera `thinlens`: depth of field as Blender/Cycles model it, from the photographer's numbers.
//
// The lens values are this plugin's parameters (its schema below); the host passes a shot's lens
// values by these names (core/render/shot_plan.cpp) and keeps only pose, sensor and resolution in
// fb_camera_setup. The f-number arrives as itself and becomes a radius here, the one translation
// on its way from the scene (docs/architecture.md, "The f-number's way").
//
// The aperture is a disk (or a regular polygon of `aperture_blades` blades, rotated) of radius
// f / (2N) at the camera origin; its x is divided by `aperture_ratio` (anamorphic bokeh). A ray
// leaves a lens point and passes through the point where the pinhole ray of its raster position
// meets the focus plane, at depth `focus_distance_m` along the view axis. This is a thin lens
// obeying 1/f' = 1/D_obj + 1/D_img with the image distance D_img equal to the nominal focal length
// f (so f' = f D_f / (D_f + f)): the field of view does not change with focus, as in Blender
// (docs/camera-model.md derives it and the circle of confusion c = A |D - D_f| / D * f' / (D_f -
// f')).
//
// Sensor: SIMPLE weighs every ray 1 (Cycles' pixel values). PHYSICAL weighs it with the camera
// equation H = L t (pi / 4N^2) cos^4(theta) (ISO 12232), times ISO/100 and the aperture's area
// relative to the round one, theta being the chief ray's angle to the axis.
//
// A tracked clip's lens distortion (filmback/lens_distortion.h) moves each film position to the
// undistorted one before all this, so the bokeh is the undistorted image's, distorted with it as
// the Movie Distortion node would; a position the model cannot undistort has weight 0.
#include <filmback/camera_projection.h>
#include <filmback/lens_distortion.h>
#include <filmback/plugin_sdk.h>
#include <filmback/sampling.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace {

using fb::Vec2f;

constexpr double kPi = std::numbers::pi;

// Blender's names and units (Camera > Depth of Field); the bounds are the ones Blender and
// fb_camera_setup's readers accept. A focus distance bounded by infinity admits "inf".
constexpr fb_param_desc kParams[] = {
    {"fstop", FB_PARAM_FLOAT, "2.8", "f-number", nullptr, 1e-6, 1e6,
     "aperture as an f-number N: radius f / 2N"},
    {"focus_distance_m", FB_PARAM_FLOAT, "inf", "m", nullptr, 1e-6, HUGE_VAL,
     "distance of the plane in focus along the view axis; inf: focused at infinity"},
    FB_APERTURE_SHAPE_PARAMS,
    FB_LENS_DISTORTION_PARAMS,
};
constexpr auto kFstop = fb::param<double>(kParams, "fstop");
constexpr auto kFocusDistance = fb::param<double>(kParams, "focus_distance_m");
constexpr auto kBlades = fb::param<int>(kParams, "aperture_blades");
constexpr auto kRotation = fb::param<double>(kParams, "aperture_rotation_rad");
constexpr auto kRatio = fb::param<double>(kParams, "aperture_ratio");

class ThinLens {
 public:
  ThinLens(const fb_value* values, const fb_camera_setup& s)
      : plane_(fb::view_plane(s)),
        near_(s.clip_near_m),
        far_(s.clip_far_m),
        radius_m_(s.focal_length_mm * 1e-3 / (2 * kFstop(values))),
        focus_m_(kFocusDistance(values)),
        blades_(uint32_t(kBlades(values))),
        rotation_(float(kRotation(values))),
        inverse_ratio_(float(1 / kRatio(values))),
        focal_mm_(s.focal_length_mm),
        fstop_(kFstop(values)),
        distortion_(fb::lens_distortion_params(kParams, values)),
        width_px_(s.image_width_px),
        height_px_(s.image_height_px) {
    if (s.projection != FB_PROJECTION_PERSPECTIVE)
      throw std::invalid_argument("a thin lens needs a perspective projection");
    if (blades_ == 1 || blades_ == 2)
      throw std::invalid_argument("an aperture has 0 (round) or at least 3 blades");
    if (!(s.focal_length_mm > 0) || !(near_ >= 0) || !(far_ > near_))
      throw std::invalid_argument("focal length and clip range must be positive and non-empty");
    if (const char* problem = fb::view_plane_problem(plane_, s))
      throw std::invalid_argument(problem);
    if (s.sensor_model == FB_SENSOR_PHYSICAL) {
      const double n = double(blades_), fstop = kFstop(values);
      const double area_vs_disk =
          (blades_ ? n * std::sin(2 * kPi / n) / (2 * kPi) : 1.0) / kRatio(values);
      exposure_ = float(kPi / (4 * fstop * fstop) * s.exposure_time_s * s.iso / 100 * area_vs_disk);
    }
  }

  uint32_t needs() const { return FB_CAMERA_NEEDS_LENS; }

  // The aperture as a length, and the focal length the lens really has when the image distance
  // stays f while it focuses at D (1/f' = 1/D + 1/f; docs/camera-model.md).
  std::string describe() const {
    char text[256];
    int n = std::snprintf(text, sizeof text, "aperture diameter: %.6g mm (f/%.6g)\n",
                          focal_mm_ / fstop_, fstop_);
    if (!std::isinf(focus_m_))
      std::snprintf(text + n, sizeof text - size_t(n),
                    "effective focal length: %.6g mm (focused at %.6g m; image distance %.6g mm)\n",
                    focal_mm_ * focus_m_ * 1e3 / (focus_m_ * 1e3 + focal_mm_), focus_m_, focal_mm_);
    return text;
  }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    fb::Vec2d film{s.film_x, s.film_y};
    bool undistorted = true;
    if (!distortion_.identity()) {
      const std::optional<fb::Vec2d> u = distortion_.undistorted_film(film, width_px_, height_px_);
      undistorted = u.has_value();
      if (u) film = *u;
    }
    // The pinhole ray's direction at unit depth, and where it meets the focus plane.
    const double x = (film.x - plane_.cx) / plane_.fx;
    const double y = -(film.y - plane_.cy) / plane_.fy;
    const Vec2f lens =
        fb::sample_aperture({s.lens_u, s.lens_v}, blades_, rotation_, inverse_ratio_);
    const double lx = lens.x * radius_m_, ly = lens.y * radius_m_;
    // Towards the focus point (x D_f, y D_f, -D_f); at infinite focus, parallel to the chief ray.
    const bool infinite = std::isinf(focus_m_);
    const double dx = infinite ? x : x * focus_m_ - lx, dy = infinite ? y : y * focus_m_ - ly;
    const double dz = infinite ? -1.0 : -focus_m_;
    const double inv_length = 1.0 / std::sqrt(dx * dx + dy * dy + dz * dz);
    ray.origin[0] = float(lx);
    ray.origin[1] = float(ly);
    ray.origin[2] = 0.f;
    ray.direction[0] = float(dx * inv_length);
    ray.direction[1] = float(dy * inv_length);
    ray.direction[2] = float(dz * inv_length);
    const double cos_axis = -dz * inv_length;  // clip by depth along the view axis
    ray.t_min = float(near_ / cos_axis);
    ray.t_max = float(far_ / cos_axis);
    if (exposure_ > 0.f) {
      const float cos2 = float(1.0 / (x * x + y * y + 1.0));  // the chief ray's cos^2(theta)
      ray.weight = exposure_ * cos2 * cos2;
    } else {
      ray.weight = 1.f;
    }
    if (!undistorted) ray.weight = 0.f;  // beyond the model's fold: black
  }

 private:
  fb::ViewPlane plane_;
  double near_, far_;
  double radius_m_, focus_m_;
  uint32_t blades_;
  float rotation_, inverse_ratio_;
  double focal_mm_, fstop_;
  float exposure_ = 0.f;  // 0: the simple sensor
  fb::LensDistortion distortion_;
  double width_px_, height_px_;
};

constexpr fb_camera_api kApi = fb::camera_api<ThinLens>();
constexpr fb_plugin kPlugin = fb::describe(
    "thinlens", "1.3.0",
    "Thin lens with Blender's f-number, focus distance, blades, rotation, anamorphic ratio and "
    "a tracked clip's lens distortion",
    kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
