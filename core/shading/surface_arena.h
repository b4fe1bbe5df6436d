// Storage for the surfaces of the hits an integrator's radiance() call traces (fb_hit.surface
// points into it), reused by the next call, so that no hit allocates once the first batches have
// warmed it up. Two lifetimes, as docs/plugins.md ("Surfaces") states them: the surfaces of a
// batch of camera rays (intersect_batch) stay until the call returns; those of single rays
// (intersect) sit in a ring and stay until kRing more single rays have been traced, which is more
// than an integrator holds (a path tracer needs the last one).
#pragma once

#include <memory>
#include <vector>

#include "core/shading/surface.h"

namespace fb {

class SurfaceArena {
 public:
  static constexpr size_t kChunk = 256;
  static constexpr size_t kRing = 64;

  SurfaceArena() : ring_(std::make_unique<Surface[]>(kRing)) {}

  // For a hit of a batch: kept until reset().
  Surface& batch_next() {
    const size_t chunk = batch_used_ / kChunk;
    if (chunk == batch_.size()) batch_.push_back(std::make_unique<Surface[]>(kChunk));
    return batch_[chunk][batch_used_++ % kChunk];
  }
  // For a hit of a single ray: kept for the next kRing - 1 single hits.
  Surface& ring_next() { return ring_[ring_used_++ % kRing]; }
  void reset() { batch_used_ = 0; }

 private:
  std::vector<std::unique_ptr<Surface[]>> batch_;
  size_t batch_used_ = 0;
  std::unique_ptr<Surface[]> ring_;
  size_t ring_used_ = 0;
};

}  // namespace fb
