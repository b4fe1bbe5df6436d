// The node hierarchy and its animation: what a scene needs to place its instances, cameras and
// lights at any time. Time is the glTF timeline in seconds (t = frame / fps, frame 0 at t = 0,
// as Blender's exporter writes it). Curves follow glTF 2.0 §3.11 and Appendix C: STEP, LINEAR
// (slerp for rotations) and CUBICSPLINE (Hermite) interpolation, clamped outside their keys.
// A static scene has no curves, and every query answers from the rest pose.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <filmback/vec.h>

#include "core/math/transform.h"

namespace fb {

constexpr uint32_t kNoNode = 0xffffffffu;
// An instance outside any node tree, its own asset (Scene::assets).
constexpr uint32_t kNoAsset = 0xffffffffu;
constexpr uint32_t kNoCurve = 0xffffffffu;

enum class Interpolation : uint8_t { kStep, kLinear, kCubicSpline };
// kWeights: a mesh's morph target weights (kept by its MeshDeformation, not by the hierarchy).
enum class TrsPath : uint8_t { kTranslation = 0, kRotation = 1, kScale = 2, kWeights = 3 };

// glTF 2.0 Appendix C's spherical linear interpolation of unit quaternions, along the shorter
// arc; nearly parallel ones are interpolated linearly and normalised.
Quatd slerp(Quatd a, Quatd b, double t);

// One animated property of one node: a glTF channel with its sampler.
struct AnimationCurve {
  uint32_t node = kNoNode;
  TrsPath path = TrsPath::kTranslation;
  Interpolation interpolation = Interpolation::kLinear;
  std::vector<double> times_s;  // strictly increasing, finite
  // width() numbers per key; CUBICSPLINE keys hold in-tangent, value, out-tangent (glTF order).
  std::vector<double> values;
  uint32_t weight_count = 0;  // kWeights: values per key, one per morph target

  uint32_t width() const {
    return path == TrsPath::kRotation ? 4 : path == TrsPath::kWeights ? weight_count : 3;
  }
  // The property at time t into out[0 .. width()): x, y, z (and w for a rotation, then a unit
  // quaternion), or one weight per morph target.
  void evaluate(double t, double* out) const;
  // Whether the value can differ anywhere in [t0, t1]; false means constant there, exactly.
  bool varies(double t0, double t1) const;
};

// Translation, rotation (x, y, z, w), scale: a glTF node's local transform is T·R·S.
struct Trs {
  Vec3d translation{0, 0, 0};
  Quatd rotation;
  Vec3d scale{1, 1, 1};
  Transform matrix() const;
};

struct SceneNode {
  uint32_t parent = kNoNode;  // always an earlier node
  Transform local;            // rest pose: glTF's matrix, or rest.matrix()
  Trs rest;                   // unused for a matrix node, which animation cannot target
  Transform world;            // rest pose in the world
  std::array<uint32_t, 3> curves{kNoCurve, kNoCurve, kNoCurve};  // by TrsPath
  bool animated = false;  // this node or an ancestor has a curve (set by finish())
};

// A render's moments on the scene's timeline, in absolute seconds: the frame's time and the
// shutter's open interval [open_s, close_s].
struct ShotTimes {
  double frame_s = 0;
  double open_s = 0, close_s = 0;
  bool shutter_open() const { return close_s > open_s; }
  // Where everything that does not move within the shutter is placed (and every light): the
  // frame's time, or the shutter's end nearest to it when the shutter leaves it out, where what
  // is still during the shutter already stands. A zero-length shutter is the instant it names.
  double still_s() const { return std::clamp(frame_s, open_s, close_s); }
};

struct NodeHierarchy {
  std::vector<SceneNode> nodes;
  std::vector<AnimationCurve> curves;

  // Appends a node below `parent` (kNoNode for a root) with its rest local transform.
  uint32_t add_node(uint32_t parent, const Transform& local, const Trs& rest);
  // Links each curve to its node and marks animated subtrees; call after adding curves.
  void finish();
  bool has_animation() const { return !curves.empty(); }
  Transform world_from_node(uint32_t node, double time_s) const;
  // Whether the node's world transform can change within [t0, t1].
  bool moves(uint32_t node, double t0, double t1) const;
};

}  // namespace fb
