#include "core/scene/solid.h"

#include <algorithm>
#include <cmath>

#include "core/scene/lathe.h"

namespace fb {

namespace {

constexpr double kInf = HUGE_VAL;

Bounds3d everything() {
  return {{-kInf, -kInf, -kInf}, {kInf, kInf, kInf}};
}

}  // namespace

Bounds3d object_bounds(const Solid& primitive) {
  switch (primitive.kind) {
    case SolidKind::kSphere:
    case SolidKind::kBox:
    case SolidKind::kSuperellipsoid:
    case SolidKind::kCylinder:
      return {{-1, -1, primitive.kind == SolidKind::kCylinder ? 0.0 : -1.0}, {1, 1, 1}};
    case SolidKind::kCone: {
      const double r = std::max(std::abs(primitive.radius0), std::abs(primitive.radius1));
      return {{-r, -r, 0}, {r, r, 1}};
    }
    case SolidKind::kTorus: {
      const double r = std::abs(primitive.radius1);
      return {{-1 - r, -1 - r, -r}, {1 + r, 1 + r, r}};
    }
    case SolidKind::kOutline: {
      const Outline& o = *primitive.outline;
      if (!primitive.conic) return {{o.lo.x, o.lo.y, 0}, {o.hi.x, o.hi.y, 1}};
      Bounds3d box;  // the outline's box scaled by each end height
      for (double z : {primitive.radius0, primitive.radius1})
        for (Vec2d p : {o.lo, o.hi})
          box.extend({p.x * z, p.y * z, z});
      return box;
    }
    case SolidKind::kBlob:
      return blob_bounds(primitive.blob);
    case SolidKind::kSor:
      return sor_bounds(primitive.sor);
    case SolidKind::kLathe:
      return lathe_bounds(*primitive.outline);
    case SolidKind::kLemon:
      return lemon_bounds(primitive.lemon);
    case SolidKind::kSphereSweep:
      return sphere_sweep_bounds(*primitive.sweep);
    case SolidKind::kIsosurface:
      return isosurface_bounds(*primitive.isosurface);
    case SolidKind::kJuliaFractal:
      return julia_fractal_bounds(*primitive.julia);
    default:  // kHalfSpace, kDisc (half-spaces), kPolynomial: unbounded
      return everything();
  }
}

Bounds3d solid_bounds(const Solid& solid, const Transform& space_from_world) {
  return solid.inverse ? everything() : uncomplemented_bounds(solid, space_from_world);
}

Bounds3d uncomplemented_bounds(const Solid& solid, const Transform& space_from_world) {
  if (solid.is_primitive()) {
    const Bounds3d box = object_bounds(solid);
    if (!box.finite()) return everything();
    const Transform space_from_object = space_from_world * solid.world_from_object;
    Bounds3d bounds;
    for (int i = 0; i < 8; ++i)
      bounds.extend(space_from_object.point(
          {i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z}));
    return bounds;
  }
  if (solid.kind == SolidKind::kUnion) {
    Bounds3d bounds;
    for (const Solid& child : solid.children)
      bounds.extend(solid_bounds(child, space_from_world));
    return bounds;
  }
  Bounds3d bounds = everything();  // kIntersection: within every child
  for (const Solid& child : solid.children) {
    const Bounds3d b = solid_bounds(child, space_from_world);
    bounds.lo = max(bounds.lo, b.lo), bounds.hi = min(bounds.hi, b.hi);
  }
  return bounds;
}

}  // namespace fb
