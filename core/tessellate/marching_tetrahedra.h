// A set given by its inside test as triangles, for `filmback convert`: marching tetrahedra over a
// grid spanning a box, each vertex found by bisection on a grid edge the set's boundary crosses,
// so that it lies on the surface; the mesh strays from the surface between its vertices, by about
// a cell's chord error. The isosurface (tessellate_isosurface.h) and the julia fractal use it.
#pragma once

#include <cstdint>

#include <filmback/vec.h>

#include "core/math/bounds.h"
#include "core/scene/scene.h"

namespace fb {

// The grid's cells on the box's longest side, at most: 128^3 cells, 2.1 million inside tests,
// whatever the tolerance asks.
constexpr uint32_t kMarchedMaxCells = 128;

// What the mesher asks of the set.
class MarchedSet {
 public:
  virtual bool holds(Vec3d p) const = 0;
  // The outward normal (any length) at p on the boundary; `outside`: the outside end of the
  // bisected grid edge p lies on, a 2^-24 cell from it.
  virtual Vec3d normal(Vec3d p, Vec3d outside) const = 0;
  // Whether a triangle about `centre` is surface (all are unless the set says otherwise).
  virtual bool keeps(Vec3d /*centre*/) const { return true; }

 protected:
  ~MarchedSet() = default;
};

// Appends the boundary of the set within `box` to `mesh`: counter-clockwise seen from outside,
// with the set's normals. `cells` on the longest side (clamped to 2 .. kMarchedMaxCells), cubes as
// near as may be. `closed`: the grid reaches half a cell past the box, so that where the set
// meets the box its boundary there is meshed too.
void march_tetrahedra(const MarchedSet& set, const Bounds3d& box, uint32_t cells, bool closed,
                      TriangleMesh& mesh);

}  // namespace fb
