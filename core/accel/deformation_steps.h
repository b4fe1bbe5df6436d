// The poses a deformed mesh (core/scene/mesh_deformation.h) is drawn with: once at the still
// time, or, when its pose or its node's placement changes within the open shutter, at evenly
// spaced times over it that Embree's multi-segment vertex motion interpolates linearly
// (docs/scenes.md, "Skins and morph targets").
#pragma once

#include <vector>

#include "core/accel/motion_tolerance.h"
#include "core/math/transform.h"
#include "core/scene/mesh_deformation.h"
#include "core/scene/scene.h"

namespace fb {

struct DeformationSteps {
  std::vector<double> times_s;                // on the scene's timeline, increasing
  std::vector<Transform> render_from_object;  // one per time
  std::vector<DeformedShape> shapes;          // one per time: positions and normals
  // A skin's or morph's pose at the first time, whole (texture coordinates, tangents); empty for
  // evaluated shapes, which keep the scene's mesh for those.
  TriangleMesh first_pose;
};

// Evaluated shapes (FILMBACK_deformation) that differ get the file's count of steps, which are
// the shapes themselves. A skin or morph (or a single evaluated shape on a moving node) gets the
// fewest 2^n + 1 steps (n = 0, 1, ..., at most kMaxEvaluatedShapes) for which every vertex's
// pose at the middle of each segment lies within `tolerance` of the segment's linear
// interpolation, in render space; the middles are the next n's new steps, so the search poses the
// mesh at most twice the steps it keeps.
DeformationSteps deformation_steps(const Scene& scene, const MeshInstance& instance,
                                   const MeshDeformation& deformation,
                                   const Transform& render_from_world, const ShotTimes& times,
                                   const MotionTolerance& tolerance);

}  // namespace fb
