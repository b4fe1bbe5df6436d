// Deterministic sample values: each is a function of (seed, pixel, sample index, dimension) only,
// so an image is identical for any thread count or tile order (docs/conventions.md). Values are
// hashed, never drawn from a stream, and lie on the 2^-24 grid the plugin ABI promises.
//
// The camera's own dimensions (filter offset, lens point, time) are stratified: each pair is an
// Owen-scrambled Sobol (0,2)-sequence, shuffled and scrambled per pixel and per pair (Burley 2020,
// "Practical Hash-based Owen Scrambling", JCGT 9(4)), so 2^k samples of a pixel form a (0,k,2)-net
// and any sample count stays unbiased. The integrator's dimensions are independent hashes.
#pragma once

#include <cstdint>

#include <filmback/vec.h>

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

// Sobol's second generator matrix (the Pascal matrix mod 2: direction numbers v_0 = 2^31,
// v_i = v_{i-1} ^ (v_{i-1} >> 1)) applied to each byte of a 24-bit index: three lookups.
struct PascalByteTables {
  uint32_t byte[3][256];
};
constexpr PascalByteTables pascal_byte_tables() {
  PascalByteTables t{};
  uint32_t v[24] = {};
  v[0] = 1u << 31;
  for (int i = 1; i < 24; ++i)
    v[i] = v[i - 1] ^ (v[i - 1] >> 1);
  for (int b = 0; b < 3; ++b)
    for (uint32_t x = 0; x < 256; ++x)
      for (int bit = 0; bit < 8; ++bit)
        if (x >> bit & 1) t.byte[b][x] ^= v[8 * b + bit];
  return t;
}
inline constexpr PascalByteTables kPascal = pascal_byte_tables();

class PixelSampler {
 public:
  explicit PixelSampler(uint64_t seed) : seed_(seed) {}

  // An independent uniform value in [0, 1).
  float get(const SampleKey& key) const {
    return to_unit(uint32_t(hash(key, key.sample_index) >> 32));
  }

  // Dimensions (key.dimension, key.dimension + 1) as one stratified 2-D point.
  Vec2f get_2d(const SampleKey& key) const {
    return sobol_2d(pair_seed(key.pixel_x, key.pixel_y, key.dimension), key.sample_index);
  }
  // Dimension key.dimension alone, stratified: the first coordinate of get_2d's sequence.
  float get_1d(const SampleKey& key) const {
    return sobol_1d(pair_seed(key.pixel_x, key.pixel_y, key.dimension), key.sample_index);
  }

  // The same, split so that a loop over a pixel's samples hashes the pixel once.
  uint32_t pair_seed(uint32_t pixel_x, uint32_t pixel_y, uint32_t dimension) const {
    return uint32_t(hash({pixel_x, pixel_y, 0, dimension}, 0xffffffffu));
  }
  static Vec2f sobol_2d(uint32_t seed, uint32_t sample_index) {
    const uint32_t index = shuffled(sample_index, seed);
    return {to_unit(owen_scramble(sobol(index, 0), seed ^ 0xa511e9b3u)),
            to_unit(owen_scramble(sobol(index, 1), seed ^ 0x63d83595u))};
  }
  static float sobol_1d(uint32_t seed, uint32_t sample_index) {
    return to_unit(owen_scramble(sobol(shuffled(sample_index, seed), 0), seed ^ 0xa511e9b3u));
  }

  // The first two dimensions of Sobol's sequence as 32-bit fractions, for indices below 2^24.
  static uint32_t sobol(uint32_t index, int dimension) {
    if (dimension == 0) return reverse_bits(index);
    return kPascal.byte[0][index & 0xff] ^ kPascal.byte[1][(index >> 8) & 0xff] ^
           kPascal.byte[2][index >> 16];
  }

  // Nested uniform (Owen) scrambling of a 32-bit fraction: each bit is flipped by a hash of the
  // bits above it (Laine and Karras 2011's permutation on the reversed bits, as Burley 2020).
  static uint32_t owen_scramble(uint32_t x, uint32_t seed) {
    x = reverse_bits(x);
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return reverse_bits(x);
  }

  // SplitMix64's finaliser (Steele et al. 2014): a bijective avalanche mix. Also the hash of
  // stochastic transparency (core/accel/render_geometry.cpp).
  static uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }

 private:
  // Owen-scrambled sample order (Burley 2020, section 4): 2^k consecutive samples of a pixel are
  // still 2^k consecutive, aligned Sobol indices. Index bits from 24 up would reach only output
  // bits that to_unit() drops (both generator matrices are upper triangular), so they are cleared.
  static uint32_t shuffled(uint32_t sample_index, uint32_t seed) {
    return owen_scramble(sample_index, seed) & 0xffffffu;
  }

  static float to_unit(uint32_t bits) { return float(bits >> 8) * 0x1p-24f; }  // exact, < 1

  static uint32_t reverse_bits(uint32_t x) {
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  }

  uint64_t hash(const SampleKey& key, uint32_t index) const {
    uint64_t h = mix(seed_ ^ 0x9e3779b97f4a7c15ull);
    h = mix(h ^ ((uint64_t(key.pixel_x) << 32) | key.pixel_y));
    return mix(h ^ ((uint64_t(index) << 32) | key.dimension));
  }

  uint64_t seed_;
};

}  // namespace fb
