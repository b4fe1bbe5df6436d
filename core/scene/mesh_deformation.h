// Meshes whose vertices move, not only their placement: glTF morph targets (glTF 2.0 §3.7.2.2)
// and skins (§3.8, "Skins"), morphing first, as the spec orders; or the shapes an exporter
// evaluated at times over the shutter (Blender's depsgraph, FILMBACK_deformation).
// The importer keeps what the file says; the render poses each deformed mesh at its motion steps
// (posed_mesh), where the joints' animation is known (docs/scenes.md, "Skins and morph targets").
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <filmback/vec.h>

#include "core/math/transform.h"
#include "core/scene/animation.h"

namespace fb {

struct Scene;
struct TriangleMesh;

// A skin bound to one mesh's vertices. The posed vertex is
//   v' = Σ_i w_i · (world_from_node(joint_i, t) · inverse_bind_i) · v
// in world space: the skinned node's own transform is ignored, as the spec says.
struct SkinBinding {
  std::vector<uint32_t> joint_nodes;     // in Scene::hierarchy, one per joint of the skin
  std::vector<Transform> inverse_binds;  // one per joint, finite
  uint32_t influences_per_vertex = 0;    // four per JOINTS_n / WEIGHTS_n set
  // Vertex-major, influences_per_vertex each: an index into joint_nodes and its weight. The
  // weights of a vertex sum to one (the importer normalises them).
  std::vector<uint32_t> joints;
  std::vector<float> weights;
};

// A primitive's morph targets: v' = v + Σ_t w_t · d_t for positions, normals and tangents' xyz
// (glTF 2.0 §3.7.2.2), with the weights at the time.
struct MorphTargets {
  // Per target, one displacement per vertex, or none where the target has no such attribute.
  std::vector<std::vector<Vec3f>> positions, normals, tangents;
  std::vector<double> weights;  // one per target: the node's, else the mesh's, else zeros
  std::optional<AnimationCurve> weight_curve;  // a `weights` channel on the node

  bool empty() const { return weights.empty(); }
  std::vector<double> weights_at(double time_s) const;
};

// A deformed mesh's vertices at one time: positions, and normals (none: the mesh's own).
struct DeformedShape {
  std::vector<Vec3f> positions, normals;
};

// Shapes an exporter evaluated (docs/scenes.md, "Blender's evaluated deformation"): the mesh at
// each of `times_s`, seconds relative to the frame's time, increasing. Between two times a vertex
// moves linearly, as Embree interpolates between motion steps; before the first and after the
// last it stays.
struct EvaluatedShapes {
  std::vector<double> times_s;
  std::vector<DeformedShape> shapes;  // one per time, every one of the mesh's vertex count

  bool empty() const { return times_s.empty(); }
  DeformedShape at(double time_from_frame_s) const;
};

// How many evaluated shapes a file may give a primitive: Embree's limit on motion steps
// (RTC_MAX_TIME_STEP_COUNT), which is also Cycles' (Object::MAX_MOTION_STEPS).
constexpr size_t kMaxEvaluatedShapes = 129;

// Scene::meshes[mesh] holds the base shape (the bind pose) as read; posed_mesh makes the posed
// copies the render traces. A deformed mesh is drawn by exactly one instance: at the identity
// when skinned, else by its node.
struct MeshDeformation {
  uint32_t mesh = 0;
  MorphTargets morph;               // empty: none
  std::optional<SkinBinding> skin;  // none: only morphed
  // Not empty: the exporter's shapes, which replace the morph targets and the skin.
  EvaluatedShapes evaluated;
};

// `mesh` displaced by `morph`'s targets with `weights` (one per target); normals and tangents
// are renormalised where a target moved them.
void apply_morph(const MorphTargets& morph, const std::vector<double>& weights, TriangleMesh& mesh);

// The skinning matrices at `time_s`: world_from_node(joint_i, t) · inverse_bind_i per joint.
std::vector<Transform> joint_matrices(const SkinBinding& skin, const NodeHierarchy& hierarchy,
                                      double time_s);

// `mesh` (the bind pose) posed by `skin` with the joint matrices `joint_matrices`: positions by
// the blended matrix, normals by its inverse transpose (renormalised), tangents' xyz by the
// matrix (renormalised, w kept).
void pose_mesh(const SkinBinding& skin, const std::vector<Transform>& joint_matrices,
               TriangleMesh& mesh);

// The deformed mesh `deformation` of `scene` posed at `time_s` (seconds on the scene's
// timeline): morphed, then skinned. Not for evaluated shapes (EvaluatedShapes::at).
TriangleMesh posed_mesh(const Scene& scene, const MeshDeformation& deformation, double time_s);

// The most shapes the render stores for `deformation` when it moves within the shutter: the
// evaluated shapes' count when there are several, else kMaxEvaluatedShapes (a skin's or morph's
// count follows its motion, core/accel/deformation_steps.h, up to that).
uint32_t deformation_motion_steps(const MeshDeformation& deformation);

// Whether the pose can change within [t0, t1]: a joint moves, the weights' curve varies, or the
// evaluated shapes differ (whatever the times: the shutter may be any of the frame's).
bool deforms(const MeshDeformation& deformation, const NodeHierarchy& hierarchy, double t0,
             double t1);

}  // namespace fb
