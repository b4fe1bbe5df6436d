// Solids for the intersection tests: a primitive placed by a transform, a set operation, a ball.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/scene/solid.h"

namespace fb::test {

// A RenderSolid's reach that clips nothing the tests place (they stay within metres of the origin).
inline const Bounds3d kReach{{-1e7, -1e7, -1e7}, {1e7, 1e7, 1e7}};

inline Solid primitive(SolidKind kind, const Transform& world_from_object = Transform(),
                       uint32_t material = 0) {
  Solid s;
  s.kind = kind;
  s.name = "test";
  s.world_from_object = world_from_object;
  s.material = material;
  return s;
}

inline Solid csg(SolidKind kind, std::vector<Solid> children) {
  Solid s;
  s.kind = kind;
  s.name = "csg";
  s.children = std::move(children);
  return s;
}

inline Solid ball(Vec3d centre, double radius, uint32_t material) {
  return primitive(SolidKind::kSphere,
                   Transform::translate(centre) * Transform::scale({radius, radius, radius}),
                   material);
}

// The set's complement.
inline Solid inverted(Solid s) {
  s.inverse = !s.inverse;
  return s;
}

}  // namespace fb::test
