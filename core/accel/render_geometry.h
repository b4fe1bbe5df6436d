// The scene's triangles in render space (world translated so the camera is at the origin, then
// narrowed to float), with an Embree 3 BVH over them. A mesh used once is flattened: its triangles
// are stored in render space, which keeps traversal single-level. A mesh several instances use is
// stored once in object space with its own BVH, and each instance is an Embree instance of it
// (core/accel/instancing.h says which; docs/architecture.md, "Instances"); its hits are rebuilt
// in render space with the same arithmetic as a flattened copy's. An instance that moves while the
// shutter is open is stored at several evenly spaced times (its vertices, or its transform when
// instanced) and intersected at the ray's time through Embree's motion blur; everything else is
// stored once, at the frame's time (docs/camera-model.md, "Time and motion").
// Analytic solids (Scene::solids) are Embree user geometry intersected exactly, at the frame's
// time (core/accel/solid_intersect.h).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

#include "core/accel/instancing.h"
#include "core/accel/motion_tolerance.h"
#include "core/math/transform.h"
#include "core/scene/scene.h"
#include "core/shading/surface_arena.h"
#include "core/texture/ray_footprint.h"
#include "core/texture/surface_shader.h"

struct RTCFilterFunctionNArguments;  // <embree3/rtcore.h>
struct RTCRayHit;

namespace fb {

class RenderSolid;
struct EmbreeSolid;

struct EmissiveTriangle {
  Vec3f p0, p1, p2;
  Vec3f normal;  // unit, front side (counter-clockwise winding)
  float area;
  uint32_t material;
  uint32_t mesh = 0, primitive = 0;  // where it is in the geometry, for textured emission
  // Moving during the shutter: where it is depends on the ray's time, so light sampling leaves it
  // to BSDF sampling (p0, p1, p2 hold its pose at shutter open).
  bool moving = false;
};

class RenderGeometry {
 public:
  // `scene` must outlive the geometry: the surface shader reads its materials at every hit.
  RenderGeometry(const Scene& scene, const Transform& render_from_world, const ShotTimes& times,
                 const MotionTolerance& tolerance, Instancing instancing = Instancing::kRepeated);
  ~RenderGeometry();
  RenderGeometry(const RenderGeometry&) = delete;
  RenderGeometry& operator=(const RenderGeometry&) = delete;

  // With an arena, each hit gets its surface (fb_hit.surface) from it; without, none (nullptr).
  // Textures are read over the ray's footprint (core/texture/ray_footprint.h); none: at their
  // finest level.
  bool intersect(const fb_ray& ray, fb_hit& hit, SurfaceArena* arena = nullptr,
                 const FootprintSource& footprint = {}) const;
  // Embree's ray stream with the coherent flag; a miss gets hit.t = +infinity. The footprint's
  // differentials, when it has them, are one per ray.
  void intersect_coherent(const fb_ray* rays, size_t count, fb_hit* hits,
                          SurfaceArena* arena = nullptr,
                          const FootprintSource& footprints = {}) const;
  bool occluded(const fb_ray& ray) const;

  // What a ray meets first, by what names it (Cryptomatte, core/film/cryptomatte.h): the scene
  // object, an index into Scene::instances or, past them, into Scene::solids; its material; and
  // where (the Vector pass places the point: core/render/motion_vectors.h): how far along the ray
  // and, on a mesh, the triangle of the scene's mesh with the weights u, v of its corners 1 and 2
  // in the scene mesh's order (0 on a solid). None for a miss. Embree's intersection only, no hit
  // record: a render that asks for Cryptomatte or Vector traces each camera ray once more, and
  // one that does not pays nothing.
  struct SurfaceIdentity {
    uint32_t object;
    uint32_t material;
    float t;
    uint32_t primitive = 0;
    float u = 0.f, v = 0.f;
  };
  std::optional<SurfaceIdentity> identify(const fb_ray& ray) const;

  const std::vector<EmissiveTriangle>& emitters() const { return emitters_; }
  // Radiance an emitter sends from barycentrics (u, v) (Embree's: p0 + u (p1 - p0) + v (p2 - p0)),
  // its emissive texture evaluated there.
  Rgb emission_at(const EmissiveTriangle& emitter, float u, float v) const;
  Vec3f bounds_centre() const { return centre_; }
  float bounds_radius() const { return radius_; }
  size_t triangle_count() const { return triangle_count_; }  // rendered: each instance's copy
  size_t instanced_count() const;                            // instances traced as Embree instances
  size_t moving_instance_count() const { return moving_instances_; }
  uint32_t most_motion_steps() const { return most_motion_steps_; }  // 1 when nothing moves

  // Bytes held by every RenderGeometry alive in this process: render-space vertices, normals,
  // texture coordinates, tangents, indices and emitters, and what Embree's memory monitor reports
  // for their devices (the BVH). Process-wide because a RenderJob keeps its geometry to itself;
  // `filmback bench` holds one job at a time and reports this as the geometry it renders.
  static size_t live_bytes();

 private:
  struct Mesh;
  struct Instance;
  struct HitTriangle;
  // What a hit record is filled for: the ray, where its surface goes (none: no surface),
  // whether it is a camera ray (Cycles samples closures defensively there, ShadingFrame), and
  // what its footprint is computed from.
  struct HitRequest {
    const fb_ray& ray;
    SurfaceArena* arena;
    bool camera;
    FootprintSource footprint;
  };
  // The hit record of what Embree found (a flattened triangle, an instanced one or a solid);
  // false if there is none.
  bool fill_embree_hit(const RTCRayHit& found, const HitRequest& request, fb_hit& hit) const;
  // Triangle `primitive` of a flattened mesh, or of an instance, in render space at Embree's
  // normalised time.
  static HitTriangle flat_triangle(const Mesh& mesh, uint32_t primitive, float time);
  HitTriangle instanced_triangle(const Instance& instance, uint32_t primitive, float time) const;
  // The hit record for barycentrics (u, v) at distance t on `triangle`.
  void fill_hit(const HitTriangle& triangle, float u, float v, float t, const HitRequest& request,
                fb_hit& hit) const;
  static SurfacePoint surface_point(const HitTriangle& triangle, float u, float v);
  // The hit record of a ray Embree found ending on solid geometry `id`; false if it does not.
  bool fill_solid_hit(unsigned id, const HitRequest& request, fb_hit& hit) const;
  // The material's textures at `point` into the hit's surface fields, and its surface from the
  // request's arena when there is one.
  void shade(uint32_t material, const SurfacePoint& point, const HitRequest& request,
             fb_hit& hit) const;
  static void alpha_filter(const RTCFilterFunctionNArguments* args);
  // Embree's time in [0, 1] across the open shutter, for a ray's time relative to the frame.
  float embree_time(float time_s) const;
  // `source` gives the triangles, material and texturing; `shapes`, a deformed mesh's positions
  // and normals at each step; empty: the source's at every step.
  Mesh build_mesh(const MeshInstance& instance,
                  const std::vector<Transform>& render_from_object_steps,
                  const TriangleMesh& source, const std::vector<DeformedShape>& shapes = {});
  // A skinned, morphed or evaluated mesh, posed at each motion step (docs/scenes.md, "Skins and
  // morph targets", "Blender's evaluated deformation").
  void add_deformed_mesh(const Scene& scene, const MeshInstance& instance,
                         const MeshDeformation& deformation, const Transform& render_from_world,
                         const ShotTimes& times, const MotionTolerance& tolerance);
  // The object-space copy of scene mesh `mesh` with its own Embree scene, made at its first use.
  uint32_t prototype_of(const Scene& scene, uint32_t mesh);
  // `corners`: the mesh's object-space box corners.
  void add_instance(const Scene& scene, const MeshInstance& instance,
                    const std::vector<Vec3d>& corners,
                    std::vector<Transform> render_from_object_steps);
  void attach_instances();
  // The constructor's steps: the Embree device and scene; the emitters of an emissive mesh; a mesh
  // and the solids into the Embree scene; and the bytes this object holds (live_bytes()).
  void open_embree();
  void add_emitters(Mesh& mesh, bool moving);
  void attach_mesh(Mesh mesh);
  void attach_solids(const Scene& scene, const Transform& render_from_world);
  size_t count_own_bytes() const;
  std::unique_ptr<SurfaceShader> shader_;    // materials' textures, evaluated at each hit
  std::vector<Mesh> meshes_;                 // indexed by Embree geometry ID
  std::vector<RenderSolid> solids_;          // Embree geometry IDs from meshes_.size() on
  std::vector<Mesh> prototypes_;             // object space; geometry 0 of their own Embree scene
  std::vector<uint32_t> prototype_of_mesh_;  // per scene mesh; FB_NONE until made
  std::vector<Instance> instances_;  // Embree geometry IDs from meshes_.size() + solids_.size()
  std::vector<EmbreeSolid> embree_solids_;  // what Embree's callbacks see of each solid
  std::vector<EmissiveTriangle> emitters_;
  Bounds3d bounds_;  // of every vertex at every motion step
  Vec3f centre_;
  float radius_ = 0.f;
  size_t triangle_count_ = 0;
  uint32_t object_count_ = 0;  // the scene's instances: solids' SurfaceIdentity::object follow
  size_t moving_instances_ = 0;
  uint32_t most_motion_steps_ = 1;
  float open_s_ = 0.f, inverse_duration_ = 0.f;  // the shutter relative to the frame's time
  size_t own_bytes_ = 0;  // this object's share of live_bytes(), Embree's aside
  struct Embree;
  std::unique_ptr<Embree> embree_;
};

}  // namespace fb
