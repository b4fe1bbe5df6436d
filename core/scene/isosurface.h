// POV-Ray's isosurface (SolidKind::kIsosurface; POV-Ray 3.7 reference, "Isosurface"): the points
// of its container where a user function is below the threshold. The function has no closed-form
// roots, so a ray samples it with the step its Lipschitz bound (max_gradient) makes safe, as
// POV-Ray does: where |f - threshold| = v, no root lies closer than v / max_gradient. What the
// intersector and the tessellator need of it: the crossings along a ray, the inside test, the
// gradient; docs/pov.md, "Isosurface".
#pragma once

#include <memory>

#include <filmback/vec.h>

#include "core/function/user_function.h"
#include "core/math/bounds.h"

namespace fb {

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

// f(p) - threshold: negative inside. NaN (a square root of a negative number) counts as outside.
double isosurface_value(const Isosurface& iso, Vec3d p);

// Whether p lies in the container (on its boundary: yes).
bool isosurface_container_holds(const Isosurface& iso, Vec3d p);

// Whether p is inside: in the container and below the threshold.
bool isosurface_contains(const Isosurface& iso, Vec3d p);

// The ray's walk through the container from t_in towards t_out (stopping once past `t_stop`):
// `inside_at_entry`, then the crossings' t in increasing order (at most kIsosurfaceMaxCrossings),
// each refined to well below `accuracy`. `complete` is false when a cap stopped the walk at
// `t_end` before t_out.
struct IsosurfaceWalk {
  bool inside_at_entry = false;
  int count = 0;
  double crossings[kIsosurfaceMaxCrossings];
  bool complete = true;
  double t_end = 0;
};
IsosurfaceWalk isosurface_walk(const Isosurface& iso, Vec3d o, Vec3d d, double t_in, double t_out,
                               double t_stop);

// grad f at p by central differences over a step of a tenth of the accuracy: the surface's
// outward normal direction (f grows outwards).
Vec3d isosurface_gradient(const Isosurface& iso, Vec3d p);

// The container's outward normal at p on its boundary.
Vec3d isosurface_container_normal(const Isosurface& iso, Vec3d p);

// The function over the points of a grid of (cells_per_axis + 1)^3 spanning the container's box
// that lie in the container, for
// what a scene should hear at load: the steepest difference quotient along the grid's edges
// (between finite samples; at most the function's true Lipschitz constant), for POV-Ray's warning
// that max_gradient is too low, and how many samples were finite (none: the function has no
// surface).
struct IsosurfaceProbe {
  double steepest_gradient = 0;
  int finite_samples = 0;
};
IsosurfaceProbe isosurface_probe(const Isosurface& iso, int cells_per_axis);

}  // namespace fb
