// The scene's triangles in render space (world translated so the camera is at the origin, then
// narrowed to float), with an Embree 3 BVH over them. Instances are flattened: every triangle
// is stored once per instance, which keeps traversal single-level and fastest
// (docs/architecture.md).
#pragma once

#include <memory>
#include <vector>

#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

#include "core/math/transform.h"
#include "core/scene/scene.h"

namespace fb {

struct EmissiveTriangle {
  Vec3f p0, p1, p2;
  Vec3f normal;  // unit, front side (counter-clockwise winding)
  float area;
  uint32_t material;
};

class RenderGeometry {
 public:
  RenderGeometry(const Scene& scene, const Transform& render_from_world);
  ~RenderGeometry();
  RenderGeometry(const RenderGeometry&) = delete;
  RenderGeometry& operator=(const RenderGeometry&) = delete;

  bool intersect(const fb_ray& ray, fb_hit& hit) const;
  // Embree's ray stream with the coherent flag; a miss gets hit.t = +infinity.
  void intersect_coherent(const fb_ray* rays, size_t count, fb_hit* hits) const;
  bool occluded(const fb_ray& ray) const;

  const std::vector<EmissiveTriangle>& emitters() const { return emitters_; }
  Vec3f bounds_centre() const { return centre_; }
  float bounds_radius() const { return radius_; }
  size_t triangle_count() const { return triangle_count_; }

 private:
  struct Mesh;
  // The hit record for barycentrics (u, v) at distance t on triangle `primitive` of `mesh`.
  static void fill_hit(const Mesh& mesh, uint32_t primitive, float u, float v, float t,
                       fb_hit& hit);
  std::vector<Mesh> meshes_;  // indexed by Embree geometry ID
  std::vector<EmissiveTriangle> emitters_;
  Vec3f centre_;
  float radius_ = 0.f;
  size_t triangle_count_ = 0;
  struct Embree;
  std::unique_ptr<Embree> embree_;
};

}  // namespace fb
