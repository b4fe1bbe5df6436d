// Deterministic sample values: each is a function of (seed, pixel, sample index, dimension) only,
// so an image is identical for any thread count or tile order (docs/conventions.md). This is the
// independent sampler; its values are hashed, never drawn from a stream.
#pragma once

#include <cstdint>

namespace fb {

// Dimensions the render loop spends before the integrator's first one.
enum SampleDimension : uint32_t {
  kFilterDimension = 0,  // two: x and y offsets
  kLensDimension = 2,    // two: only when the camera needs them
  kTimeDimension = 4,    // one: only when the scene moves
  kIntegratorDimension = 5
};

struct SampleKey {
  uint32_t pixel_x, pixel_y, sample_index, dimension;
};

class IndependentSampler {
 public:
  explicit IndependentSampler(uint64_t seed) : seed_(seed) {}
  float get(const SampleKey& key) const {
    uint64_t h = mix(seed_ ^ 0x9e3779b97f4a7c15ull);
    h = mix(h ^ ((uint64_t(key.pixel_x) << 32) | key.pixel_y));
    h = mix(h ^ ((uint64_t(key.sample_index) << 32) | key.dimension));
    return float(h >> 40) * 0x1p-24f;  // 24 bits: exactly representable, always < 1
  }

 private:
  // SplitMix64's finaliser (Steele et al. 2014): a bijective avalanche mix.
  static uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  uint64_t seed_;
};

}  // namespace fb
