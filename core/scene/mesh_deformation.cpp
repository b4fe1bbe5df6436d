#include "core/scene/mesh_deformation.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/scene/scene.h"

namespace fb {
namespace {

// Σ_i w_i · joint_matrix_i for one vertex (glTF 2.0 §3.8.3, the "skin matrix"). The bottom row
// is kept exactly (0, 0, 0, 1): weights rounded to float may sum to 1 ± 1e-7, which must not
// turn the affine blend into a projective one.
Transform skin_matrix(const SkinBinding& skin, const std::vector<Transform>& joint_matrices,
                      size_t vertex) {
  std::array<double, 16> rows{};
  const size_t first = vertex * skin.influences_per_vertex;
  for (size_t k = first; k < first + skin.influences_per_vertex; ++k) {
    const double w = skin.weights[k];
    if (w == 0) continue;
    const Transform& joint = joint_matrices[skin.joints[k]];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        rows[size_t(r * 4 + c)] += w * joint(r, c);
  }
  rows[15] = 1;
  return Transform::from_rows(rows);
}

// A deformed direction, unit length; `fallback` where the blend collapses it (a joint scaled to
// zero), so that no NaN reaches the render.
Vec3f deformed_direction(Vec3d v, Vec3f fallback) {
  const double n = length(v);
  return n > 0 && std::isfinite(n) ? Vec3f(v / n) : fallback;
}

}  // namespace

std::vector<Transform> joint_matrices(const SkinBinding& skin, const NodeHierarchy& hierarchy,
                                      double time_s) {
  std::vector<Transform> out;
  out.reserve(skin.joint_nodes.size());
  for (size_t j = 0; j < skin.joint_nodes.size(); ++j)
    out.push_back(hierarchy.world_from_node(skin.joint_nodes[j], time_s) * skin.inverse_binds[j]);
  return out;
}

void pose_mesh(const SkinBinding& skin, const std::vector<Transform>& joint_matrices,
               TriangleMesh& mesh) {
  std::vector<std::array<float, 4>>& tangents = mesh.texturing.tangents;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Transform m = skin_matrix(skin, joint_matrices, v);
    mesh.positions[v] = Vec3f(m.point(Vec3d(mesh.positions[v])));
    if (!mesh.normals.empty())
      mesh.normals[v] =
          deformed_direction(m.normal_transform().vector(Vec3d(mesh.normals[v])), mesh.normals[v]);
    if (!tangents.empty()) {
      std::array<float, 4>& t = tangents[v];
      const Vec3f bind{t[0], t[1], t[2]};
      const Vec3f posed = deformed_direction(m.vector(Vec3d(bind)), bind);
      t[0] = posed.x, t[1] = posed.y, t[2] = posed.z;
    }
  }
}

std::vector<double> MorphTargets::weights_at(double time_s) const {
  if (!weight_curve) return weights;
  std::vector<double> out(weights.size());
  weight_curve->evaluate(time_s, out.data());
  return out;
}

void apply_morph(const MorphTargets& morph, const std::vector<double>& weights,
                 TriangleMesh& mesh) {
  // Targets at rest are skipped: weights of zero leave the mesh bit for bit.
  std::vector<size_t> moving;
  for (size_t t = 0; t < weights.size(); ++t)
    if (weights[t] != 0) moving.push_back(t);
  if (moving.empty()) return;
  // Σ_t w_t · d_t[v] over the targets that have the attribute, in double.
  const auto displaced = [&](const std::vector<std::vector<Vec3f>>& d, Vec3d base, size_t v) {
    for (size_t t : moving)
      if (!d[t].empty()) base += weights[t] * Vec3d(d[t][v]);
    return base;
  };
  std::vector<std::array<float, 4>>& tangents = mesh.texturing.tangents;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    mesh.positions[v] = Vec3f(displaced(morph.positions, Vec3d(mesh.positions[v]), v));
    if (!mesh.normals.empty())
      mesh.normals[v] =
          deformed_direction(displaced(morph.normals, Vec3d(mesh.normals[v]), v), mesh.normals[v]);
    if (!tangents.empty()) {
      std::array<float, 4>& t = tangents[v];
      const Vec3f base{t[0], t[1], t[2]};
      const Vec3f moved = deformed_direction(displaced(morph.tangents, Vec3d(base), v), base);
      t[0] = moved.x, t[1] = moved.y, t[2] = moved.z;
    }
  }
}

DeformedShape EvaluatedShapes::at(double time_from_frame_s) const {
  const size_t n = times_s.size();
  if (n == 1 || !(time_from_frame_s > times_s.front())) return shapes.front();
  if (time_from_frame_s >= times_s.back()) return shapes.back();
  size_t k = 1;
  while (times_s[k] < time_from_frame_s)
    ++k;
  const double f = (time_from_frame_s - times_s[k - 1]) / (times_s[k] - times_s[k - 1]);
  if (f == 0) return shapes[k - 1];
  const DeformedShape &a = shapes[k - 1], &b = shapes[k];
  DeformedShape out;
  out.positions.reserve(a.positions.size());
  for (size_t v = 0; v < a.positions.size(); ++v)
    out.positions.emplace_back(Vec3d(a.positions[v]) * (1 - f) + Vec3d(b.positions[v]) * f);
  out.normals.reserve(a.normals.size());
  for (size_t v = 0; v < a.normals.size(); ++v)
    out.normals.push_back(
        deformed_direction(Vec3d(a.normals[v]) * (1 - f) + Vec3d(b.normals[v]) * f, a.normals[v]));
  return out;
}

uint32_t deformation_motion_steps(const MeshDeformation& deformation) {
  const size_t evaluated = deformation.evaluated.times_s.size();
  return uint32_t(evaluated > 1 ? evaluated : kMaxEvaluatedShapes);
}

TriangleMesh posed_mesh(const Scene& scene, const MeshDeformation& deformation, double time_s) {
  TriangleMesh mesh = scene.meshes[deformation.mesh];
  if (!deformation.morph.empty())
    apply_morph(deformation.morph, deformation.morph.weights_at(time_s), mesh);
  if (deformation.skin)
    pose_mesh(*deformation.skin, joint_matrices(*deformation.skin, scene.hierarchy, time_s), mesh);
  return mesh;
}

bool deforms(const MeshDeformation& deformation, const NodeHierarchy& hierarchy, double t0,
             double t1) {
  if (deformation.morph.weight_curve && deformation.morph.weight_curve->varies(t0, t1)) return true;
  const std::vector<DeformedShape>& shapes = deformation.evaluated.shapes;
  const auto same = [](Vec3f a, Vec3f b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  for (size_t k = 1; k < shapes.size(); ++k)
    if (!std::equal(shapes[k].positions.begin(), shapes[k].positions.end(),
                    shapes[0].positions.begin(), same))
      return true;
  if (deformation.skin)
    for (uint32_t joint : deformation.skin->joint_nodes)
      if (hierarchy.moves(joint, t0, t1)) return true;
  return false;
}

}  // namespace fb
