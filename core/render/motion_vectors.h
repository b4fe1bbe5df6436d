// Blender's Vector pass (docs/blender.md, "Passes"): where the point a camera ray meets first
// stood one frame before and will stand one frame after, in raster pixels relative to where it
// stands now, in Cycles 3.4's convention (measured): X, Y = previous minus current, Z, W =
// current minus next, y up. The point is placed by its object's transforms at the frame's time
// ± 1 / fps and projected by the camera (pose and lens track) at those times: a few matrix
// products per hit, everything else worked out once per render. Motion is rigid: a mesh's
// deformation (skins, morph targets, Blender's evaluated meshes) is not followed, only its node.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <filmback/camera_projection.h>
#include <filmback/plugin_abi.h>

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

  // X, Y, Z, W (pixels) of the point at distance `t` along camera ray `ray` (render space) on
  // object `object`. A point behind the camera at one of the times has 0 for that pair.
  std::array<float, 4> at(const fb_ray& ray, float t, uint32_t object) const;

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
};

}  // namespace fb
