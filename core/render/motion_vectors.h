// Blender's Vector pass (docs/blender.md, "Passes"): where the point a camera ray meets first
// stood one frame before and will stand one frame after, in raster pixels relative to where it
// stands now, in Cycles 3.4's convention (measured): X, Y = previous minus current, Z, W =
// current minus next, y up. The point is placed by its object's transforms at the frame's time
// ± 1 / fps and projected by the camera (pose and lens track) at those times: a few matrix
// products per hit, everything else worked out once per render. A skinned or morphed mesh that
// deforms between the frames around this one is posed at the three times once, and the point
// follows its triangle; Blender's evaluated meshes (FILMBACK_deformation) only their node.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <filmback/camera_projection.h>
#include <filmback/plugin_abi.h>

#include "core/accel/render_geometry.h"
#include "core/math/transform.h"
#include "core/scene/scene.h"

namespace fb {

struct ShotPlan;

// The pass as --passes names it; the host writes it (core/film/motion_vector_film.h), not the
// integrator.
inline constexpr const char* kVectorPass = "Vector";

class MotionVectors {
 public:
  // `scene` is the one the geometry was built from: RenderGeometry::SurfaceIdentity::object
  // indexes its instances, then its solids (which do not move). Throws UsageError for a camera
  // plugin other than Blender's projections (perspective, thinlens, orthographic), or with lens
  // distortion.
  MotionVectors(const Scene& scene, const ShotPlan& plan, const Transform& render_from_world);

  // X, Y, Z, W (pixels) of the point a camera ray `ray` (render space) met, as
  // RenderGeometry::identify tells it. A point behind the camera at one of the times has 0 for
  // that pair.
  std::array<float, 4> at(const fb_ray& ray, const RenderGeometry::SurfaceIdentity& met) const;

 private:
  // The camera at one moment: where it stands and how it projects.
  struct CameraMoment {
    Transform camera_from_world;
    ViewPlane plane;
  };
  // Raster position of world point `p` seen from `camera`; false when it is behind the camera.
  bool raster(const CameraMoment& camera, Vec3d p, Vec2d& out) const;

  bool orthographic_;
  std::array<CameraMoment, 3> cameras_;  // the previous frame, this one, the next
  Transform world_from_render_;
  // Per moving instance, the world-space map from where it is now to where it is one frame
  // before and one after; moving_of_object_ indexes it per object (kStill: it does not move).
  static constexpr uint32_t kStill = UINT32_MAX;
  std::vector<uint32_t> moving_of_object_;
  std::vector<std::array<Transform, 2>> moving_;
  // A deforming mesh: its triangles, and its vertices a frame before, at the frame and a frame
  // after, in render space (float, near the camera, as the geometry's). deformed_of_object_
  // indexes it per object (kStill: rigid).
  struct DeformedPoses {
    const std::vector<uint32_t>* indices;
    std::array<std::vector<Vec3f>, 3> render_positions;
  };
  std::vector<uint32_t> deformed_of_object_;
  std::vector<DeformedPoses> deformed_;
  // The world points a frame before, at and a frame after where `met` is on deformed mesh `d`.
  std::array<Vec3d, 3> deformed_points(const DeformedPoses& d,
                                       const RenderGeometry::SurfaceIdentity& met) const;
};

}  // namespace fb
