// Seeded random rays at a solid, and random points about it, for the tests that check each hit
// and each inside answer against the shape's own equation.
#pragma once

#include <filmback/vec.h>

#include <cstdint>
#include <random>
#include <utility>

namespace fb::test {

class RaysAtABox {
 public:
  // Rays start `distance` from `centre` and aim at points within `half` of it along each axis.
  RaysAtABox(uint64_t seed, Vec3d centre, double distance, double half)
      : rng_(seed), centre_(centre), distance_(distance), half_(half) {}

  // A unit vector towards a random point of a cube (not uniform over the sphere, nor needed).
  Vec3d direction() { return normalize(Vec3d{u_(rng_), u_(rng_), u_(rng_)}); }
  // A point within `half` of the centre along each axis.
  Vec3d in_box(double half) { return centre_ + Vec3d{u_(rng_), u_(rng_), u_(rng_)} * half; }
  // The next ray: origin and unit direction.
  std::pair<Vec3d, Vec3d> next() {
    const Vec3d from = centre_ + direction() * distance_;
    return {from, normalize(in_box(half_) - from)};
  }

 private:
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> u_{-1, 1};
  Vec3d centre_;
  double distance_, half_;
};

}  // namespace fb::test
