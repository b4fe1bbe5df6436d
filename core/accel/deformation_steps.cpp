#include "core/accel/deformation_steps.h"

#include <utility>

namespace fb {
namespace {

// Skinned and morphed positions are single precision: a pose differs from the interpolation of
// its neighbours by a few float roundings even where the motion is linear, which no tolerance
// (a zero one in tests) should count as curvature.
constexpr double kPoseRoundingRelative = 1e-6;

struct Pose {
  Transform render_from_object;
  DeformedShape shape;
};

// The deformation's pose at `t` (seconds on the scene's timeline), with the node's placement.
Pose pose_at(const Scene& scene, const MeshInstance& instance, const MeshDeformation& deformation,
             const Transform& render_from_world, const ShotTimes& times, double t,
             TriangleMesh* whole) {
  Pose pose{render_from_world * scene.world_from_object(instance, t), {}};
  if (!deformation.evaluated.empty()) {
    pose.shape = deformation.evaluated.at(t - times.frame_s);
    return pose;
  }
  TriangleMesh posed = posed_mesh(scene, deformation, t);
  pose.shape = {posed.positions, posed.normals};
  if (whole) *whole = std::move(posed);
  return pose;
}

// Whether every vertex of `middle` lies within the tolerance of the midpoint of `a` and `b`.
bool follows_chord(const Pose& a, const Pose& middle, const Pose& b,
                   const MotionTolerance& tolerance) {
  for (size_t v = 0; v < middle.shape.positions.size(); ++v) {
    const Vec3d p = middle.render_from_object.point(Vec3d(middle.shape.positions[v]));
    const Vec3d chord = (a.render_from_object.point(Vec3d(a.shape.positions[v])) +
                         b.render_from_object.point(Vec3d(b.shape.positions[v]))) *
                        0.5;
    const double distance = length(p);
    const double allowed =
        tolerance.absolute_m + tolerance.per_metre * distance + kPoseRoundingRelative * distance;
    if (!(length(p - chord) <= allowed)) return false;
  }
  return true;
}

}  // namespace

DeformationSteps deformation_steps(const Scene& scene, const MeshInstance& instance,
                                   const MeshDeformation& deformation,
                                   const Transform& render_from_world, const ShotTimes& times,
                                   const MotionTolerance& tolerance) {
  const bool moving =
      times.shutter_open() && (deforms(deformation, scene.hierarchy, times.open_s, times.close_s) ||
                               scene.moves(instance.node_index, times.open_s, times.close_s));
  DeformationSteps out;
  const auto at = [&](double t, TriangleMesh* whole) {
    return pose_at(scene, instance, deformation, render_from_world, times, t, whole);
  };
  const auto time_of = [&](size_t k, size_t segments) {
    return times.open_s + (times.close_s - times.open_s) * double(k) / double(segments);
  };
  std::vector<Pose> poses;
  if (!moving) {
    out.times_s = {times.still_s()};
    poses.push_back(at(times.still_s(), &out.first_pose));
  } else if (deformation.evaluated.times_s.size() > 1) {
    const size_t count = deformation.evaluated.times_s.size();
    for (size_t k = 0; k < count; ++k) {
      out.times_s.push_back(time_of(k, count - 1));
      poses.push_back(at(out.times_s.back(), nullptr));
    }
  } else {
    out.times_s = {times.open_s, times.close_s};
    poses.push_back(at(times.open_s, &out.first_pose));
    poses.push_back(at(times.close_s, nullptr));
    for (size_t segments = 1; 2 * segments + 1 <= kMaxEvaluatedShapes; segments *= 2) {
      std::vector<double> refined_times{out.times_s.front()};
      std::vector<Pose> refined{poses.front()};
      bool follows = true;
      for (size_t k = 0; k < segments; ++k) {
        const double middle_s = time_of(2 * k + 1, 2 * segments);
        Pose middle = at(middle_s, nullptr);
        follows = follows && follows_chord(poses[k], middle, poses[k + 1], tolerance);
        refined_times.push_back(middle_s);
        refined.push_back(std::move(middle));
        refined_times.push_back(out.times_s[k + 1]);
        refined.push_back(poses[k + 1]);
      }
      if (follows) break;
      out.times_s = std::move(refined_times);
      poses = std::move(refined);
    }
  }
  for (Pose& pose : poses) {
    out.render_from_object.push_back(pose.render_from_object);
    out.shapes.push_back(std::move(pose.shape));
  }
  return out;
}

}  // namespace fb
