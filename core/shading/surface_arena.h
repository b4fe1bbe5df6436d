// Storage for the surfaces of the hits one radiance() call traces (fb_hit.surface points into it):
// handed out in order and reused by the next call, so that no hit allocates once the first
// batches have warmed it up. It holds the most recent kCapacity surfaces and wraps around after
// that, which is why fb_hit.surface stays valid only until kCapacity more hits have been traced
// in the same call (docs/plugins.md, "Surfaces"): far more than any integrator keeps.
#pragma once

#include <memory>
#include <vector>

#include "core/shading/surface.h"

namespace fb {

class SurfaceArena {
 public:
  static constexpr size_t kChunk = 256;
  static constexpr size_t kCapacity = size_t(1) << 16;

  Surface& next() {
    if (used_ == kCapacity) used_ = 0;
    const size_t chunk = used_ / kChunk;
    if (chunk == chunks_.size()) chunks_.push_back(std::make_unique<Surface[]>(kChunk));
    return chunks_[chunk][used_++ % kChunk];
  }
  void reset() { used_ = 0; }

 private:
  std::vector<std::unique_ptr<Surface[]>> chunks_;
  size_t used_ = 0;
};

}  // namespace fb
