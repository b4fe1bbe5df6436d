// POV-Ray's isosurface (SolidKind::kIsosurface; POV-Ray 3.7 reference, "Isosurface"): the points
// of its container where a user function is below the threshold. The function has no closed-form
// roots, so a ray samples it with the step its Lipschitz bound (max_gradient) makes safe, as
// POV-Ray does: where |f - threshold| = v, no root lies closer than v / max_gradient. Here its
// data and its container; what evaluates the function (the walk along a ray, the inside test,
// the gradient) is core/function/isosurface_function.h. docs/pov.md, "Isosurface".
#pragma once

#include <memory>

#include <filmback/vec.h>

#include "core/math/bounds.h"

namespace fb {

class UserFunction;  // core/function/user_function.h

struct Isosurface {
  std::shared_ptr<const UserFunction> function;  // of x, y, z in the object space
  double threshold = 0;
  // The interval the root search stops refining at (object units, > 0), and the bound on |grad f|
  // the sampling steps trust (> 0); POV-Ray's defaults.
  double accuracy = 0.001;
  double max_gradient = 1.1;
  // contained_by: box { lo, hi } or sphere { centre, radius } (POV-Ray's default: box -1, 1).
  bool sphere_container = false;
  Vec3d box_lo{-1, -1, -1}, box_hi{1, 1, 1};
  Vec3d centre{0, 0, 0};
  double radius = 1;
};

// A ray finds at most this many crossings of the function (the rest of its chord of the
// container is then outside), and takes at most this many samples (likewise): the work per ray
// is bounded whatever the function, its gradient bound and its accuracy.
constexpr int kIsosurfaceMaxCrossings = 64;
constexpr int kIsosurfaceMaxSamples = 1 << 14;

// The container's box.
Bounds3d isosurface_bounds(const Isosurface& iso);

// The ray's parameters where o + t d enters and leaves the container; false if it misses.
bool isosurface_container_chord(const Isosurface& iso, Vec3d o, Vec3d d, double& t_in,
                                double& t_out);

// Whether p lies in the container (on its boundary: yes).
bool isosurface_container_holds(const Isosurface& iso, Vec3d p);

// The container's outward normal at p on its boundary.
Vec3d isosurface_container_normal(const Isosurface& iso, Vec3d p);

}  // namespace fb
