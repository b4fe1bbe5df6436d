// The gradient of a scalar field by central differences, to check analytic normals against.
#pragma once

#include <filmback/vec.h>

namespace fb::test {

// (f(p + h e_i) - f(p - h e_i)) / 2h for each axis i.
template <class Field>
Vec3d central_difference_gradient(const Field& f, Vec3d p, double h) {
  return Vec3d{f(p + Vec3d{h, 0, 0}) - f(p - Vec3d{h, 0, 0}),
               f(p + Vec3d{0, h, 0}) - f(p - Vec3d{0, h, 0}),
               f(p + Vec3d{0, 0, h}) - f(p - Vec3d{0, 0, h})} /
         (2 * h);
}

}  // namespace fb::test
