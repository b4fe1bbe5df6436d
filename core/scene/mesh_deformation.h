// Meshes whose vertices move, not only their placement: glTF skins (glTF 2.0 §3.8, "Skins").
// The importer keeps what the file says; the render poses each deformed mesh at the shot's still
// time (pose_deformed_meshes), where the joints' animation is known (docs/scenes.md, "Skins").
#pragma once

#include <cstdint>
#include <vector>

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

// Scene::meshes[mesh] holds the bind pose as read; posing replaces its positions, normals and
// tangents. A deformed mesh is drawn by exactly one instance, placed at the identity.
struct MeshDeformation {
  uint32_t mesh = 0;
  SkinBinding skin;
};

// The skinning matrices at `time_s`: world_from_node(joint_i, t) · inverse_bind_i per joint.
std::vector<Transform> joint_matrices(const SkinBinding& skin, const NodeHierarchy& hierarchy,
                                      double time_s);

// `mesh` (the bind pose) posed by `skin` with the joint matrices `joint_matrices`: positions by
// the blended matrix, normals by its inverse transpose (renormalised), tangents' xyz by the
// matrix (renormalised, w kept).
void pose_mesh(const SkinBinding& skin, const std::vector<Transform>& joint_matrices,
               TriangleMesh& mesh);

// Every deformed mesh of `scene` posed at `time_s` (seconds on the scene's timeline).
void pose_deformed_meshes(Scene& scene, double time_s);

}  // namespace fb
