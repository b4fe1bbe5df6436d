#include "core/render/motion.h"

namespace fb {

void CameraPath::place(const fb_camera_ray& ray, float time_s, fb_ray& out) const {
  const Transform render_from_camera =
      render_from_world_ * scene_.world_from_camera(camera_, frame_s_ + double(time_s));
  Vec3f(render_from_camera.point(Vec3d(Vec3f(ray.origin)))).store(out.origin);
  Vec3f(normalize(render_from_camera.vector(Vec3d(Vec3f(ray.direction))))).store(out.direction);
}

}  // namespace fb
