// The building blocks of the samplers (core/render/sampler.h): the first two dimensions of Sobol's
// sequence, Owen scrambling, random permutations of any length, and Morton order. Each is a pure
// function of its arguments, so samples are hashes, never streams.
#pragma once

#include <array>
#include <cstdint>

#include "core/math/random.h"

namespace fb {

constexpr uint32_t reverse_bits(uint32_t x) {
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

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

// Dimension 0 (van der Corput) or 1 of Sobol's sequence as a 32-bit fraction. Both generator
// matrices are upper triangular, so index bits from 24 up reach only output bits below 2^-24,
// which unit_float() drops: the index is taken modulo 2^24.
constexpr uint32_t sobol(uint64_t index, int dimension) {
  const uint32_t i = uint32_t(index) & 0xffffffu;
  if (dimension == 0) return reverse_bits(i);
  return kPascal.byte[0][i & 0xff] ^ kPascal.byte[1][(i >> 8) & 0xff] ^ kPascal.byte[2][i >> 16];
}

// Nested uniform (Owen) scrambling of a 32-bit fraction: each bit is flipped by a hash of the
// bits above it (Laine and Karras 2011's permutation on the reversed bits, as Burley 2020,
// "Practical Hash-based Owen Scrambling", JCGT 9(4)). Every scrambled point is uniform in [0, 1)
// and a (0,m,2)-net stays one.
constexpr uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  x = reverse_bits(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverse_bits(x);
}

// Element i of a random permutation of {0, ..., length - 1} chosen by `seed`, for any length
// (Kensler 2013, "Correlated Multi-Jittered Sampling": a bijective hash on the enclosing power of
// two, repeated until it lands below `length`; it ends because i's cycle returns below `length`).
// Each step is a bijection on k bits: xor with a constant, multiplication by an odd number,
// xor with a right shift of itself, all taken modulo 2^k.
constexpr uint32_t permute(uint32_t i, uint32_t length, uint64_t seed) {
  if (length <= 1) return 0;
  uint32_t mask = length - 1;
  mask |= mask >> 1, mask |= mask >> 2, mask |= mask >> 4, mask |= mask >> 8, mask |= mask >> 16;
  const uint32_t a = uint32_t(seed), b = uint32_t(seed >> 32);
  do {
    i ^= a;
    i = (i * 0xe170893du) & mask;
    i ^= (i & mask) >> 4;
    i ^= b;
    i = (i * 0x0929eb3fu) & mask;
    i ^= (i & mask) >> 3;
    i = (i * (b | 1u)) & mask;
    i ^= (i & mask) >> 5;
  } while (i >= length);
  return i;
}

// Interleaves the bits of x and y (x in the even bits): Morton's Z order.
constexpr uint64_t morton_2d(uint32_t x, uint32_t y) {
  const auto spread = [](uint64_t v) {
    v &= 0xffffffffull;
    v = (v | (v << 16)) & 0x0000ffff0000ffffull;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    return (v | (v << 1)) & 0x5555555555555555ull;
  };
  return spread(x) | (spread(y) << 1);
}

// The 24 permutations of {0, 1, 2, 3}, for permuting base-4 digits.
constexpr std::array<std::array<uint8_t, 4>, 24> permutations_of_four() {
  std::array<std::array<uint8_t, 4>, 24> all{};
  int n = 0;
  for (uint8_t a = 0; a < 4; ++a)
    for (uint8_t b = 0; b < 4; ++b)
      for (uint8_t c = 0; c < 4; ++c)
        for (uint8_t d = 0; d < 4; ++d)
          if (a != b && a != c && a != d && b != c && b != d && c != d) all[n++] = {a, b, c, d};
  return all;
}
inline constexpr std::array<std::array<uint8_t, 4>, 24> kPermutationsOfFour =
    permutations_of_four();

}  // namespace fb
