#include "support/pov_rays.h"

#include <cmath>
#include <numbers>

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

WorldRay pov_ray(const pov::PovCameraVectors& c, double x_px, double y_px, uint32_t width_px,
                 uint32_t height_px) {
  const double x0 = x_px / width_px - 0.5, y0 = 0.5 - y_px / height_px;
  const Vec3d across = c.right * x0 + c.up * y0;
  if (c.type == pov::CameraType::kOrthographic)
    return {pov::world_from_pov(c.location + across), normalize(pov::world_from_pov(c.direction))};
  return {pov::world_from_pov(c.location), normalize(pov::world_from_pov(c.direction + across))};
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
          normalize(camera.world_from_camera.vector(direction))};
}

}  // namespace fb::test
