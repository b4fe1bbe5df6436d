// filmback's one source of randomness: PCG's permutation (O'Neill 2014, "PCG: A Family of Simple
// Fast Space-Efficient Statistically Good Algorithms for Random Number Generation") used as a hash
// of a key, never as a stream, so every value is a function of what it is for (docs/conventions.md
// "Sampling and determinism"). Jarzynski and Olano 2020 ("Hash Functions for GPU Rendering", JCGT
// 9(3)) found one LCG step followed by PCG's output permutation the best quality-for-cost hash of
// sequential keys; this is its 64-bit form (LCG multiplier and increment of PCG64, output RXS M
// XS).
#pragma once

#include <cstdint>

namespace fb {

// A bijection of 64-bit values with full avalanche.
constexpr uint64_t pcg_hash(uint64_t key) {
  const uint64_t state = key * 6364136223846793005ull + 1442695040888963407ull;
  const uint64_t word = ((state >> ((state >> 59u) + 5u)) ^ state) * 12605985483714917081ull;
  return (word >> 43u) ^ word;
}

// Hashes of several words: each word enters a fresh permutation of everything before it.
constexpr uint64_t pcg_hash(uint64_t a, uint64_t b) {
  return pcg_hash(pcg_hash(a) ^ b);
}
constexpr uint64_t pcg_hash(uint64_t a, uint64_t b, uint64_t c) {
  return pcg_hash(pcg_hash(a, b) ^ c);
}

// The top 24 bits of a 32-bit fraction as a float in [0, 1): exact, a multiple of 2^-24 (the grid
// the plugin ABI promises for every sample value, plugin_abi.h).
constexpr float unit_float(uint32_t bits) {
  return float(bits >> 8) * 0x1p-24f;
}

}  // namespace fb
