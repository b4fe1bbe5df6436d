// What evaluating an isosurface's function gives the intersector, the tessellator and the SDL
// reader (core/scene/isosurface.h holds the isosurface): its value, the inside test, the walk
// along a ray with the step its Lipschitz bound makes safe, the gradient, and the load-time
// probe. docs/pov.md, "Isosurface".
#pragma once

#include <filmback/vec.h>

#include "core/scene/isosurface.h"

namespace fb {

// f(p) - threshold: negative inside. NaN (a square root of a negative number) counts as outside.
double isosurface_value(const Isosurface& iso, Vec3d p);

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

// The function over the points of a grid of (cells_per_axis + 1)^3 spanning the container's box
// that lie in the container, for what a scene should hear at load: the steepest difference quotient
// along the grid's edges (between finite samples; at most the function's true Lipschitz constant),
// for POV-Ray's warning that max_gradient is too low, and how many samples were finite (none: the
// function has no surface).
struct IsosurfaceProbe {
  double steepest_gradient = 0;
  int finite_samples = 0;
};
IsosurfaceProbe isosurface_probe(const Isosurface& iso, int cells_per_axis);

}  // namespace fb
