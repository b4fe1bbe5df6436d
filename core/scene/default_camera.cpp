#include "core/scene/default_camera.h"

#include <algorithm>
#include <cmath>

#include <filmback/camera_projection.h>

namespace fb {

SceneCamera frame_bounds(const Bounds3d& bounds) {
  SceneCamera camera;
  camera.name = "default";
  camera.source = "framed to the scene bounds (the scene has no camera)";
  camera.intended_aspect = 16.0 / 9.0;

  const Vec3d centre = bounds.empty() ? Vec3d{} : (bounds.lo + bounds.hi) * 0.5;
  const double radius = bounds.empty() ? 1.0 : std::max(length(bounds.hi - bounds.lo) * 0.5, 1e-6);
  const ViewPlane plane = view_plane(make_camera_setup(camera.physical, 1600, 900));
  const double half_angle = std::atan(plane.extent_y / 2.0);
  const double distance = 1.1 * radius / std::sin(half_angle);

  const Vec3d eye = centre + normalize(Vec3d{0.0, 0.25, 1.0}) * distance;
  camera.world_from_camera = Transform::look_at(eye, centre, {0.0, 1.0, 0.0});
  camera.physical.clip_near_m = std::max(1e-4, (distance - radius) * 0.5);
  return camera;
}

}  // namespace fb
