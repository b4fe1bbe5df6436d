// Analytic solids: exact primitives combined by constructive solid geometry, as POV-Ray scenes
// describe them (docs/architecture.md "Solids"). The render intersects them exactly (ray-interval
// CSG, core/accel/solid_intersect.h); what needs triangles tessellates the primitives
// (core/tessellate/tessellate.h).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/math/blob.h"
#include "core/math/bounds.h"
#include "core/math/julia_fractal.h"
#include "core/math/lemon.h"
#include "core/math/polynomial.h"
#include "core/math/sor.h"
#include "core/math/sphere_sweep.h"
#include "core/math/transform.h"
#include "core/scene/isosurface.h"
#include "core/scene/outline.h"

namespace fb {

enum class SolidKind : uint8_t {
  // Primitives, each in its own canonical object space; world_from_object places, sizes and may
  // shear or mirror it. Every primitive is a set of points (its inside) whose boundary is its
  // surface; normals point out of the set.
  kSphere,     // |p| <= 1
  kBox,        // max(|x|, |y|, |z|) <= 1
  kHalfSpace,  // z <= 0; the plane z = 0 is its surface
  kCylinder,   // x^2 + y^2 <= 1, 0 <= z <= 1; `open`: the caps bound the set but are not surface
  kCone,       // x^2 + y^2 <= r(z)^2, r(z) = radius0 + (radius1 - radius0) z, 0 <= z <= 1
  kTorus,      // (sqrt(x^2 + y^2) - 1)^2 + z^2 <= radius1^2: major radius 1 about the z axis
  // The unit disc in the plane z = 0 with a hole of radius `radius1`. Flat, so it bounds POV-Ray's
  // set for it, the half-space z <= 0 (Disc::Inside), of whose plane only the annulus is surface.
  kDisc,
  // polynomial(p) <= 0 for `polynomial`, of degree <= kMaxPolynomialDegree (15: POV-Ray's
  // quadric, cubic, quartic, poly and polynomial): unbounded in general; POV-Ray scenes bound them
  // by CSG.
  kPolynomial,
  // `outline` (core/scene/outline.h: closed curves in the xy plane, even-odd inside) swept from
  // z = 0 to z = 1: POV-Ray's prism and text; `conic`: scaled by z from the origin, {z p : p in
  // the outline} for radius0 <= z <= radius1 (POV-Ray's conic_sweep). `open`: the caps bound the
  // set but are no surface.
  kOutline,
  // (|x|^(2/e) + |y|^(2/e))^(e/n) + |z|^(2/n) <= 1 with e = radius0, n = radius1 (> 0): POV-Ray's
  // superellipsoid (core/math/superellipsoid.h), within the unit box.
  kSuperellipsoid,
  // POV-Ray's blob: its field reaches `blob.threshold` (core/math/blob.h); bounded by the
  // components of positive strength.
  kBlob,
  // POV-Ray's sor: x^2 + z^2 <= r(y)^2 between its lowest and highest y (core/math/sor.h); `open`:
  // the caps bound the set but are not surface.
  kSor,
  // POV-Ray's lathe: `outline`'s curves in the (radius, height) = (x, y) plane turned about the y
  // axis; a point is inside when the half-line from (sqrt(x^2 + z^2), y) towards +x crosses them
  // an odd number of times (POV-Ray's Lathe::Inside), so an unclosed curve bounds a set too.
  kLathe,
  // The inner part of a spindle torus between two planes (core/math/lemon.h): POV-Ray's lemon, and
  // an ovus's collar; `open`: the planes bound the set but are not surface.
  kLemon,
  // POV-Ray's sphere_sweep: the union of the spheres swept along its spline
  // (core/math/sphere_sweep.h).
  kSphereSweep,
  // POV-Ray's isosurface (core/scene/isosurface.h): where `isosurface`'s function is below its
  // threshold within its container; `open`: the container bounds the set but is no surface.
  kIsosurface,
  // POV-Ray's julia_fractal (core/math/julia_fractal.h): the points of `julia`'s slice whose
  // iterates stay bounded; within its bounding sphere.
  kJuliaFractal,
  // Set operations over `children` (world_from_object unused: children carry their placement).
  // A difference A - B is kIntersection{A, B with `inverse`}; POV-Ray's merge renders as union.
  kUnion,
  kIntersection,
};

struct Solid {
  SolidKind kind = SolidKind::kSphere;
  std::string name;  // for messages: where it came from
  Transform world_from_object;
  // kCone: base and cap radii (>= 0); kTorus, kDisc: radius1; kSuperellipsoid: exponents e, n
  double radius0 = 1, radius1 = 1;
  // kCylinder, kCone, kOutline, kSor, kLemon: no end caps; kIsosurface: no container walls
  bool open = false;
  bool conic = false;    // kOutline: a conic sweep between radius0 < radius1
  bool inverse = false;  // the complement of the set
  // Its boundary limits the set but is no surface: POV-Ray's clipped_by, which leaves the clipped
  // object open where it cuts.
  bool bounds_only = false;
  uint32_t material = 0;                   // of this primitive's surface (unused by set operations)
  Polynomial3 polynomial;                  // kPolynomial
  std::shared_ptr<const Outline> outline;  // kOutline (shared: a text's glyphs repeat), kLathe
  Blob blob;                               // kBlob
  Sor sor;                                 // kSor
  Lemon lemon;                             // kLemon
  std::shared_ptr<const SphereSweep> sweep;      // kSphereSweep
  std::shared_ptr<const Isosurface> isosurface;  // kIsosurface
  std::shared_ptr<const JuliaFractal> julia;     // kJuliaFractal
  std::vector<Solid> children;

  bool is_primitive() const { return kind < SolidKind::kUnion; }
};

// The primitive's set within its canonical object space, as a box (infinite for kHalfSpace and
// kDisc, which are unbounded sets).
Bounds3d object_bounds(const Solid& primitive);

// Bounds of the solid's set in the space `space_from_world` maps to: corners of each primitive's
// object box, combined through the tree (an intersection is bounded by its bounded children, a
// complement by nothing). Unbounded sets give infinite bounds.
Bounds3d solid_bounds(const Solid& solid, const Transform& space_from_world);
// The same before the solid's own `inverse` applies.
Bounds3d uncomplemented_bounds(const Solid& solid, const Transform& space_from_world);

}  // namespace fb
