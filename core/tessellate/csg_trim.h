// One primitive's share of a CSG solid's surface, as triangles (docs/architecture.md "Solids"):
// the primitive's tessellation, refined where other primitives' boundaries cross it and cut
// along those crossings, keeping what the render would show of it.
//
// Each vertex of the primitive's mesh lies on its surface and gets a label from the solid's set
// (CsgProbe::label): kept with the primitive's normal, kept reversed (a difference's cut), or
// dropped. Triangles are refined by longest-edge bisection (Rivara 1984: a triangle is halved at
// its longest edge, and its neighbours are halved too so that the mesh stays conforming; shapes do
// not degenerate, and long thin triangles are cut across; every new vertex is moved onto the
// exact surface) while one of these holds and the triangle is longer than the tolerance:
// - its corners are kept and dropped alike but other primitives' tessellations cross it over
//   more than twice the tolerance (a hole, or a band, inside one triangle);
// - another primitive's boundary crosses it, and the straight cut between the two edge crossings
//   strays from the true crossing curve by more than the tolerance (measured at the cut's middle
//   by bisection along the line from the lone corner);
// - two primitives' boundaries, or three labels, meet in it.
// Then each triangle whose labels differ is cut at the points where its edges cross the other
// boundary, found by bisection on the edge lifted onto the exact surface, so each cut vertex lies
// on both primitives' boundaries to 1e-7 of the tolerance, and shared by the triangles on both
// sides of the edge. So every point of the result is within the tolerance of the set's surface.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <filmback/vec.h>

#include "core/scene/scene.h"
#include "core/tessellate/csg_probe.h"
#include "core/tessellate/triangle_bvh.h"

namespace fb {

struct TrimmedSurface {
  static constexpr uint32_t kNoPartner = UINT32_MAX;
  struct Triangle {
    std::array<uint32_t, 3> v;
    std::array<Vec3d, 3> n;  // unit, out of the solid's set
  };
  std::vector<Vec3d> positions;     // world; some may be unused
  std::vector<uint32_t> partner;    // per position: on a cut, the primitive whose boundary it is on
  std::vector<Triangle> triangles;  // counter-clockwise seen from outside the set
};

struct TrimTolerances {
  double cut_m = 0;         // the largest distance allowed between a cut and the true crossing
  double mesh_m = 0;        // how far the primitive's mesh may stray from its surface
  double boundaries_m = 0;  // how far the other primitives' tessellations may stray from theirs
};

// `mesh` is primitive `leaf`'s tessellation in its object space; `boundaries` holds every
// primitive's closed tessellation in world space, tagged with its leaf index.
TrimmedSurface trim_surface(const CsgProbe& probe, size_t leaf, const TriangleMesh& mesh,
                            const TriangleBvh& boundaries, const TrimTolerances& tolerances);

}  // namespace fb
