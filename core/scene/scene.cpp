#include "core/scene/scene.h"

#include "core/util/error.h"

namespace fb {

size_t Scene::triangle_count() const {
  size_t count = 0;
  for (const MeshInstance& instance : instances)
    count += meshes[instance.mesh].triangle_count();
  return count;
}

Bounds3d Scene::world_bounds(double time_s) const {
  Bounds3d bounds;
  for (const MeshInstance& instance : instances) {
    const Transform world_from_object = this->world_from_object(instance, time_s);
    for (const Vec3f& p : meshes[instance.mesh].positions)
      bounds.extend(world_from_object.point(Vec3d(p)));
  }
  // A subdivision surface lies within its cage's convex hull (its refinement and limit masks
  // are convex combinations of cage points), so the cage bounds it before it is refined.
  for (const SubdivisionSurface& s : subdivision_surfaces) {
    const Transform world_from_object =
        this->world_from_object(MeshInstance{0, s.world_from_object, s.node, s.node_index}, time_s);
    for (const Vec3f& p : s.cage_positions)
      bounds.extend(world_from_object.point(Vec3d(p)));
  }
  for (const Solid& solid : solids) {  // half-spaces and complements are unbounded: left out
    const Bounds3d b = solid_bounds(solid, Transform());
    if (b.finite()) bounds.extend(b);
  }
  return bounds;
}

bool Scene::moves(uint32_t node_index, double t0, double t1) const {
  return node_index != kNoNode && hierarchy.moves(node_index, t0, t1);
}

namespace {

bool animated(const NodeHierarchy& hierarchy, uint32_t node_index) {
  return node_index != kNoNode && hierarchy.nodes[node_index].animated;
}

}  // namespace

Transform Scene::world_from_object(const MeshInstance& instance, double time_s) const {
  return animated(hierarchy, instance.node_index)
             ? hierarchy.world_from_node(instance.node_index, time_s)
             : instance.world_from_object;
}

Transform Scene::world_from_camera(const SceneCamera& camera, double time_s) const {
  return animated(hierarchy, camera.node_index)
             ? hierarchy.world_from_node(camera.node_index, time_s).without_scale()
             : camera.world_from_camera;
}

Transform Scene::world_from_light(const Light& light, double time_s) const {
  return animated(hierarchy, light.node_index)
             ? hierarchy.world_from_node(light.node_index, time_s).without_scale()
             : light.world_from_light;
}

const SceneCamera& find_camera(const Scene& scene, const std::string& name) {
  for (const SceneCamera& camera : scene.cameras)
    if (camera.name == name) return camera;
  std::string known;
  for (const SceneCamera& camera : scene.cameras)
    known += (known.empty() ? "" : ", ") + camera.name;
  throw UsageError("--camera '" + name + "': the scene has no camera of that name (" +
                   (known.empty() ? "it has no camera at all" : "it has: " + known) + ")");
}

}  // namespace fb
