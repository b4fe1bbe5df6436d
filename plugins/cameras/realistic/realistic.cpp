// Camera `realistic`: rays traced through a multi-element lens described in pbrt-v4's lens file
// format (core/sdk/filmback/lens_prescription.h), after pbrt-v4's RealisticCamera (Pharr, Jakob &
// Humphreys, Physically Based Rendering 4th ed., 5.3; Kolb, Mitchell & Hanrahan, "A Realistic
// Camera Model for Computer Graphics", SIGGRAPH 1995).
//
// The film is the shot's sensor (its size, fit and shift as Blender's view plane gives them); the
// lens replaces the focal length. The lens images upside down, so the raster point that sees the
// upper left of the scene lies at the lower right of the film. A ray starts at its film point,
// aims at a point drawn uniformly in the exit pupil's bounds for that film radius (exit_pupil.h),
// and is refracted through every surface; an aperture blocks it or it leaves the front element.
// The camera's origin is the lens' front principal point H, so a distant object's image has the
// pinhole camera's size for a focal length equal to the lens' effective focal length, and
// `focus_distance_m` is measured from H, as the thin lens's is from the lens (docs/camera-model.md,
// "Realistic lenses").
//
// Weight (the measurement equation, PBR 4th ed. eq. 5.4-5.6): a film point's irradiance is
// E = L * integral over the rear plane of cos^4(theta) / b^2 dA, b the film-to-rear-plane distance
// and theta the ray's angle to the axis; one sample estimates it by cos^4(theta) A / b^2, A the
// bounds' area. PHYSICAL: that times exposure time and ISO/100 (the thin lens's pi / 4N^2 cos^4 for
// a small aperture). SIMPLE: divided by its value at the film's centre, so an unvignetted centre
// pixel is the scene's radiance as in Cycles and the corners show the lens' fall-off.
#include <filmback/camera_projection.h>
#include <filmback/lens_optics.h>
#include <filmback/plugin_sdk.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "exit_pupil.h"

namespace {

using fb::LensRay;
using fb::Vec3d;

constexpr fb_param_desc kParams[] = {
    {"lens", FB_PARAM_STRING, "", "", nullptr, 0, 0,
     "lens file in pbrt-v4's format: radius, thickness, index, aperture diameter per interface, "
     "mm"},
    {"fstop", FB_PARAM_FLOAT, "0", "f-number", nullptr, 0, 1e6,
     "0: the lens wide open; else its aperture stop closed to this f-number (never opened beyond "
     "the lens' own)"},
    {"focus_distance_m", FB_PARAM_FLOAT, "inf", "m", nullptr, 1e-6, HUGE_VAL,
     "distance of the plane in focus from the lens' front principal point; the film moves"},
};
constexpr auto kLens = fb::param<const char*>(kParams, "lens");
constexpr auto kFstop = fb::param<double>(kParams, "fstop");
constexpr auto kFocusDistance = fb::param<double>(kParams, "focus_distance_m");

class Realistic {
 public:
  Realistic(const fb_value* values, const fb_camera_setup& s)
      : plane_(checked_view_plane(s)),
        sensor_mm_per_unit_(s.focal_length_mm),
        near_m_(s.clip_near_m),
        far_m_(s.clip_far_m),
        lens_(placed(values)),
        pupil_(lens_, film_radius_mm(s)) {
    const double centre = centre_irradiance_per_radiance();
    if (!(centre > 0))
      throw std::invalid_argument(std::string(kLens(values)) +
                                  ": no light reaches the film's centre through the lens");
    working_fnumber_ = std::sqrt(std::numbers::pi / (4 * centre));
    scale_ = s.sensor_model == FB_SENSOR_PHYSICAL ? s.exposure_time_s * s.iso / 100 : 1 / centre;
  }

  uint32_t needs() const { return FB_CAMERA_NEEDS_LENS; }

  // The lens' first-order numbers for `filmback info` (fb_camera_api::describe), lines
  // "name: value unit".
  std::string describe() const {
    const fb::ParaxialLens& p = paraxial_;
    char text[1024];
    std::snprintf(text, sizeof text,
                  "lens file: %s\n"
                  "effective focal length: %.6g mm\n"
                  "back focal distance: %.6g mm (rear vertex to focal point)\n"
                  "front focal distance: %.6g mm (front vertex to focal point)\n"
                  "f-number: %.4g (the lens' own: %.4g)\n"
                  "entrance pupil diameter: %.6g mm\n"
                  "exit pupil: %.6g mm in front of the rear vertex\n"
                  "film: %.6g mm behind the rear vertex (%.6g mm front vertex to film)\n"
                  "working f-number at the film's centre: %.4g (from E / L = pi / 4N^2)\n",
                  lens_path_.c_str(), p.efl_mm, p.bfl_mm, p.ffd_mm, p.fnumber, open_fnumber_,
                  p.entrance_pupil_diameter_mm, p.exit_pupil_from_rear_mm, lens_.rear_z_mm(),
                  lens_.front_z_mm(), working_fnumber_);
    return text;
  }

  void generate(const fb_camera_sample& s, fb_camera_ray& ray) const {
    // The view plane's point at unit depth, as mm on the sensor, mirrored onto the film.
    const double x = (s.film_x - plane_.cx) / plane_.fx, y = -(s.film_y - plane_.cy) / plane_.fy;
    const Vec3d film{-x * sensor_mm_per_unit_, -y * sensor_mm_per_unit_, 0};
    const double r = std::hypot(film.x, film.y);
    const fb::PupilBounds& b = pupil_.at(r);
    const double cos_phi = r > 0 ? film.x / r : 1, sin_phi = r > 0 ? film.y / r : 0;
    const double px = b.x0 + s.lens_u * (b.x1 - b.x0), py = b.y0 + s.lens_v * (b.y1 - b.y0);
    const Vec3d rear{cos_phi * px - sin_phi * py, sin_phi * px + cos_phi * py, lens_.rear_z_mm()};
    LensRay lens_ray{film, fb::normalize(rear - film)};
    const double cos_theta = lens_ray.direction.z;
    if (b.empty() || !lens_.trace(lens_ray)) {
      blocked(ray);
      return;
    }
    // Lens space (mm, +z to the object, film at 0) to camera space (m, -Z to the object, H at 0).
    const Vec3d o = lens_ray.origin, d = lens_ray.direction;
    ray.origin[0] = float(o.x * 1e-3);
    ray.origin[1] = float(o.y * 1e-3);
    ray.origin[2] = float(-(o.z - principal_z_mm_) * 1e-3);
    ray.direction[0] = float(d.x);
    ray.direction[1] = float(d.y);
    ray.direction[2] = float(-d.z);
    // Clipped by depth along the view axis from H; a ray leaving sideways (a fisheye's edge) is
    // clipped by distance instead.
    const double depth_m = (o.z - principal_z_mm_) * 1e-3;
    ray.t_min = d.z > 1e-6 ? float(std::max(0.0, (near_m_ - depth_m) / d.z)) : 0.f;
    ray.t_max = d.z > 1e-6 ? float((far_m_ - depth_m) / d.z) : float(far_m_);
    const double cos2 = cos_theta * cos_theta;
    ray.weight =
        float(cos2 * cos2 * b.area_mm2() / (lens_.rear_z_mm() * lens_.rear_z_mm()) * scale_);
  }

 private:
  // The shot's view plane, checked before the lens is read and traced.
  static fb::ViewPlane checked_view_plane(const fb_camera_setup& s) {
    if (s.projection != FB_PROJECTION_PERSPECTIVE)
      throw std::invalid_argument("a realistic lens needs a perspective projection");
    if (!(s.focal_length_mm > 0) || !(s.clip_near_m >= 0) || !(s.clip_far_m > s.clip_near_m))
      throw std::invalid_argument("focal length and clip range must be positive and non-empty");
    const fb::ViewPlane plane = fb::view_plane(s);
    if (const char* problem = fb::view_plane_problem(plane, s))
      throw std::invalid_argument(problem);
    return plane;
  }

  // Parses the lens, closes its stop, and moves the film to focus (lens_optics.h).
  fb::LensStack placed(const fb_value* values) {
    const char* path = kLens(values);
    if (!path || !*path)
      throw std::invalid_argument("the realistic camera needs a lens file: lens=PATH");
    const fb::LensPrescription open_lens = fb::read_lens_file(path);
    const fb::ParaxialLens open = fb::paraxial_lens(open_lens);
    lens_path_ = path;
    open_fnumber_ = open.fnumber;
    const fb::LensPrescription lens = fb::stopped_down(open_lens, open, kFstop(values));
    paraxial_ = fb::paraxial_lens(lens);
    const double focus_mm = kFocusDistance(values) * 1e3;
    if (!(focus_mm > paraxial_.efl_mm))
      throw std::invalid_argument("focus distance " + std::to_string(focus_mm * 1e-3) +
                                  " m is not beyond the lens' focal length " +
                                  std::to_string(paraxial_.efl_mm) + " mm");
    const double back_mm = fb::back_distance_for_focus_mm(paraxial_, focus_mm);
    if (!(back_mm > 0 && std::isfinite(back_mm)))
      throw std::invalid_argument(
          "the lens' rear focal point lies inside it: no film fits behind it");
    principal_z_mm_ = fb::front_principal_z_mm(paraxial_, back_mm);
    return fb::LensStack(lens, back_mm);
  }

  // Half the film's diagonal, mm: the farthest raster corner from the axis.
  double film_radius_mm(const fb_camera_setup& s) const {
    double r = 0;
    for (const double px : {0.0, double(s.image_width_px)})
      for (const double py : {0.0, double(s.image_height_px)})
        r = std::max(r, std::hypot((px - plane_.cx) / plane_.fx, (py - plane_.cy) / plane_.fy));
    return r * sensor_mm_per_unit_;
  }

  // E / L at the film's centre: the integral of cos^4(theta) / b^2 over the pupil, by a midpoint
  // rule on a 128 x 128 grid over its bounds.
  double centre_irradiance_per_radiance() const {
    constexpr int kGrid = 128;
    const fb::PupilBounds& b = pupil_.at(0);
    if (b.empty()) return 0;
    const double dx = (b.x1 - b.x0) / kGrid, dy = (b.y1 - b.y0) / kGrid, bz = lens_.rear_z_mm();
    double sum = 0;
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        LensRay ray{{0, 0, 0},
                    fb::normalize(Vec3d{b.x0 + (i + 0.5) * dx, b.y0 + (j + 0.5) * dy, bz})};
        const double c = ray.direction.z;
        if (lens_.trace(ray)) sum += c * c * c * c;
      }
    return sum * dx * dy / (bz * bz);
  }

  static void blocked(fb_camera_ray& ray) {
    ray = {{0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}, 0.f, 0.f, 0.f};
  }

  fb::ViewPlane plane_;
  double sensor_mm_per_unit_;  // sensor mm per unit of the view plane at unit depth
  double near_m_, far_m_;
  std::string lens_path_;
  double open_fnumber_ = 0;
  fb::ParaxialLens paraxial_{};
  double principal_z_mm_ = 0;  // H, from the film
  fb::LensStack lens_;
  fb::ExitPupil pupil_;
  double working_fnumber_ = 0;  // from the centre's irradiance: E / L = pi / (4 N_w^2)
  double scale_ = 1;
};

constexpr fb_camera_api kApi = fb::camera_api<Realistic>();
constexpr fb_plugin kPlugin =
    fb::describe("realistic", "1.0.0",
                 "Rays traced through a multi-element lens file (pbrt-v4's format): exit pupil, "
                 "focus by moving the film, the measurement equation's weights",
                 kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
