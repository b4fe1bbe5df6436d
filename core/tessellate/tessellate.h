// Triangle meshes of analytic primitives (core/scene/solid.h) to a stated chord tolerance, for
// what needs triangles (`filmback convert` to glTF); core/tessellate/tessellate_csg.h builds CSG
// from them.
#pragma once

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"

namespace fb {

struct TessellationOptions {
  // The largest distance allowed between the mesh and the surface, in world metres, and as a
  // fraction of the primitive's bounding radius in the world; the smaller applies (<= 0: unused).
  // By default relative only: a silhouette within a thousandth of the object's size is within a
  // pixel until the object spans a thousand pixels, at any scale.
  double tolerance_m = 0;
  double relative_tolerance = 1e-3;
  // A half-space becomes a square of this half-size (world metres) in its plane, centred on the
  // point of the plane nearest `plane_centre`.
  double plane_half_size_m = 1e4;
  Vec3d plane_centre{0, 0, 0};
  // Per circle, at most this many segments: the tolerance is not met past it (a torus 1e6 times
  // wider than the tolerance).
  uint32_t max_segments = 4096;
};

// The largest distance allowed between the primitive's surface and its mesh, world metres.
double tessellation_tolerance_m(const Solid& primitive, const TessellationOptions& options);

// Reports a primitive whose tessellation came out empty (a polynomial has none yet).
void warn_untessellated(const Solid& primitive, Diagnostics& diagnostics);

// The primitive as a mesh in its object space (instance it with world_from_object), with outward
// counter-clockwise faces and the surface's own normals at the vertices, and sharp edges
// (box, caps) split. Every point of the mesh lies within the tolerance of the surface
// (core/tessellate/tessellate_test.cpp measures it). The mesh takes the primitive's material and
// name.
TriangleMesh tessellate(const Solid& primitive, const TessellationOptions& options);

// Replaces scene.solids by meshes and instances: a primitive by its mesh in its object space, any
// other solid (CSG, an inverted primitive) by the meshes of its surface
// (core/tessellate/tessellate_csg.h). Half-spaces become squares about the scene's first camera
// (else the origin) reaching at least options.plane_half_size_m and ten times as far as the bounded
// geometry. A solid with no surface (an empty intersection) is reported.
void tessellate_solids(Scene& scene, TessellationOptions options, Diagnostics& diagnostics);

}  // namespace fb
