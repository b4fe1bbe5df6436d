// POV-Ray's blob (POV-Ray 3.7 reference, "Blob"): the set where the field
// F(p) = sum_i s_i (1 - q_i(p) / r_i^2)^2, over the components whose region (q_i < r_i^2) holds p,
// reaches the threshold. q_i is the squared distance, in the component's own space, to its centre
// (a sphere component) or to its axis segment (a cylinder component: hemispherical ends). Along a
// ray, q_i is quadratic in t wherever the component's regime does not change, so between the
// points where the ray enters or leaves a region or crosses a cylinder's end plane, F is a
// quartic in t, whose roots the polynomial solver finds exactly.
#pragma once

#include <vector>

#include <filmback/vec.h>

#include "core/math/bounds.h"
#include "core/math/transform.h"

namespace fb {

struct BlobComponent {
  Transform component_from_blob;  // the inverse of the component's own transforms
  Vec3d a{0, 0, 0}, b{0, 0, 0};   // a sphere's centre a; a cylinder's axis from a to b
  double radius = 1, strength = 1;
  bool cylinder = false;
};

struct Blob {
  double threshold = 1;  // > 0: outside every component the field is 0, outside the set
  std::vector<BlobComponent> components;
};

double blob_field(const Blob& blob, Vec3d p);
Vec3d blob_gradient(const Blob& blob, Vec3d p);  // grad F: the outward normal is its opposite

// The boxes of the components of positive strength (only they can reach the threshold).
Bounds3d blob_bounds(const Blob& blob);

// At most this many crossings blob_crossings reports for the blob (four a quartic piece).
size_t blob_max_crossings(const Blob& blob);

// The t where F(o + t d) - threshold changes between > 0 and <= 0, ascending. The storage is the
// calling thread's, reused by its next call: it grows to the largest blob a thread meets and
// then no ray allocates.
const std::vector<double>& blob_crossings(const Blob& blob, Vec3d o, Vec3d d);

}  // namespace fb
