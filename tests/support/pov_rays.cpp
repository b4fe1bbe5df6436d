#include "support/pov_rays.h"

#include <cmath>
#include <numbers>

#include "core/math/constants.h"
#include "core/render/plugin_choice_loader.h"
#include "importers/pov/pov_space.h"
#include "support/plugins.h"

namespace fb::test {

Transform pov_rotate(Vec3d degrees) {
  const auto about = [](Vec3d axis, double deg) {
    const double half = deg * std::numbers::pi / 360;
    const Vec3d v = axis * std::sin(half);
    return Transform::rotate({v.x, v.y, v.z, std::cos(half)});
  };
  return about({0, 0, 1}, degrees.z) * about({0, 1, 0}, degrees.y) * about({1, 0, 0}, degrees.x);
}

namespace {

// POV-Ray's Compute_Axis_Rotation_Transform (Faux & Pratt) applied to v: the turn by `angle`
// about unit(axis), counterclockwise seen from the axis' tip in POV-Ray's numbers (Rodrigues).
Vec3d turned(Vec3d v, Vec3d axis, double angle) {
  const Vec3d k = normalize(axis);
  return v * std::cos(angle) + cross(k, v) * std::sin(angle) +
         k * (dot(k, v) * (1 - std::cos(angle)));
}

// Polar rays of the fisheye and omnimax: phi as POV-Ray takes it, asin(v / r) or pi minus it.
Vec3d polar(double u, double v, double r, double theta, Vec3d R, Vec3d U, Vec3d D) {
  const double phi = r == 0 ? 0 : u < 0 ? kPi - std::asin(v / r) : std::asin(v / r);
  return R * (std::cos(phi) * std::sin(theta)) + U * (std::sin(phi) * std::sin(theta)) +
         D * std::cos(theta);
}

}  // namespace

WorldRay pov_ray(const pov::PovCameraVectors& c, double x_px, double y_px, uint32_t width_px,
                 uint32_t height_px) {
  using pov::CameraType;
  const double x0 = x_px / width_px - 0.5, y0 = 0.5 - y_px / height_px;
  const Vec3d across = c.right * x0 + c.up * y0;
  const auto ray = [](Vec3d origin, Vec3d direction) {
    return WorldRay{pov::world_from_pov(origin), normalize(pov::world_from_pov(direction))};
  };
  const WorldRay none{pov::world_from_pov(c.location), {0, 0, -1}, 0};
  // SetupCamera normalises the vectors of these types, after taking |right| and |up|.
  const Vec3d R = normalize(c.right), U = normalize(c.up), D = normalize(c.direction);
  const double rl = length(c.right), ul = length(c.up);
  const double angle = c.angle_deg * kPi / 180;
  switch (c.type) {
    case CameraType::kOrthographic:
      return ray(c.location + across, c.direction);
    case CameraType::kFisheye: {
      const double u = 2 * x0 * rl, v = 2 * y0 * ul, r = std::sqrt(u * u + v * v);
      if (r > 1) return none;
      return ray(c.location, polar(u, v, r, r * angle / 2, R, U, D));
    }
    case CameraType::kOmnimax: {
      double u = 2 * x0, v = 2 * y0;
      const double aspect = rl / ul;
      if (aspect > 1) {
        if (aspect > 1.283458) {
          u *= aspect / 1.283458;
          v = (v - 1) / 1.283458 + 1;
        } else {
          v = (v - 1) / aspect + 1;
        }
      } else {
        v /= aspect;
      }
      const double r = std::sqrt(u * u + v * v);
      if (r > 1) return none;
      const double theta = 1.411269 * r - 0.09439 * r * r * r + 0.25674 * r * r * r * r * r;
      const double phi = r == 0 ? 0 : u < 0 ? kPi - std::asin(v / r) : std::asin(v / r);
      if (std::sin(phi) * std::sin(theta) < std::tan(135 * kPi / 180) * std::cos(theta))
        return none;
      return ray(c.location, polar(u, v, r, theta, R, U, D));
    }
    case CameraType::kPanoramic: {  // the vectors as they are
      const double l = (1 - x_px / width_px) * kPi, m = kPi / 2 * 2 * y0;
      const double t =
          std::abs(kPi / 2 - std::abs(m)) < 1e-10 ? std::copysign(2e10, m) : std::tan(m);
      return ray(c.location, c.right * std::cos(l) + c.up * t + c.direction * std::sin(l));
    }
    case CameraType::kUltraWideAngle: {
      const double a = x0 * angle, b = y0 * angle * ul / rl;
      return ray(c.location, R * std::sin(a) + U * std::sin(b) + D * (std::cos(a) * std::cos(b)));
    }
    case CameraType::kCylinder: {
      const double a = x0 * angle, b = y0 * angle;
      switch (c.cylinder_type) {
        case 1:
          return ray(c.location, R * std::sin(a) + U * (y0 * ul) + D * std::cos(a));
        case 2:
          return ray(c.location, R * (x0 * rl) + U * std::sin(b) + D * std::cos(b));
        case 3:
          return ray(c.location + U * (y0 * ul), R * std::sin(a) + D * std::cos(a));
        default:
          return ray(c.location + R * (x0 * rl), U * std::sin(b) + D * std::cos(b));
      }
    }
    case CameraType::kSpherical: {  // the vectors as they are: turns about right, then up
      const double h = x0 * c.angle_h_deg * kPi / 180, v = y0 * c.angle_v_deg * kPi / 180;
      return ray(c.location, turned(turned(c.direction, c.right, -v), c.up, h));
    }
    default:
      return ray(c.location, c.direction + across);
  }
}

std::unique_ptr<CameraInstance> make_camera_plugin(const pov::PovCamera& camera, uint32_t width_px,
                                                   uint32_t height_px) {
  Scene scene;
  scene.cameras.push_back(camera.camera);
  scene.settings.pixel_aspect = camera.pixel_aspect;
  RenderOptions options;
  options.width = width_px, options.height = height_px;
  return load_camera(loader(), plan_shot(scene, options));
}

WorldRay filmback_ray(const CameraInstance& plugin, const SceneCamera& camera,
                      const fb_camera_sample& sample) {
  fb_camera_ray ray;
  plugin.generate_rays({&sample, 1}, &ray);
  const Vec3d origin{ray.origin[0], ray.origin[1], ray.origin[2]};
  const Vec3d direction{ray.direction[0], ray.direction[1], ray.direction[2]};
  return {camera.world_from_camera.point(origin),
          normalize(camera.world_from_camera.vector(direction)), ray.weight};
}

}  // namespace fb::test
