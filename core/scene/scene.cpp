#include "core/scene/scene.h"

namespace fb {

size_t Scene::triangle_count() const {
  size_t count = 0;
  for (const MeshInstance& instance : instances)
    count += meshes[instance.mesh].triangle_count();
  return count;
}

Bounds3d Scene::world_bounds() const {
  Bounds3d bounds;
  for (const MeshInstance& instance : instances)
    for (const Vec3f& p : meshes[instance.mesh].positions)
      bounds.extend(instance.world_from_object.point(Vec3d(p)));
  return bounds;
}

}  // namespace fb
