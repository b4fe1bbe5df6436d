#include "core/render/sampler.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/util/error.h"

namespace fb {
namespace {

constexpr const char* kNames[] = {"independent", "stratified", "sobol", "zsobol"};

uint32_t ceil_log2(uint32_t n) {
  return n <= 1 ? 0 : uint32_t(std::bit_width(n - 1));
}

// A nested random permutation of the base-4 digits of a `bits`-bit value, from the top (Ahmed and
// Wonka 2020): each digit is permuted by one of the 24 permutations of four, chosen by a hash of
// the digits above it and its place, so each node of the 4-ary tree reorders its own children.
// An odd lowest bit is flipped, or not, the same way. A bijection on [0, 2^bits).
uint64_t permute_digits(uint64_t value, uint32_t bits, uint64_t key) {
  uint64_t out = 0;
  uint32_t shift = bits;
  while (shift >= 2) {
    shift -= 2;
    const uint64_t above = value >> (shift + 2);
    const uint32_t digit = uint32_t(value >> shift) & 3u;
    const uint32_t choice = uint32_t(pcg_hash(key, above, shift) % 24);
    out |= uint64_t(kPermutationsOfFour[choice][digit]) << shift;
  }
  if (shift == 1) out |= (value ^ pcg_hash(key, value >> 1, 1)) & 1u;
  return out;
}

// A value in [cell / cells, (cell + 1) / cells) on the 2^-24 grid, `jitter` placing it inside.
float in_stratum(uint32_t cell, uint32_t cells, uint32_t jitter) {
  return unit_float(uint32_t(((uint64_t(cell) << 32) + jitter) / cells));
}

}  // namespace

SamplerKind parse_sampler_kind(const std::string& text, const char* option) {
  for (size_t i = 0; i < std::size(kNames); ++i)
    if (text == kNames[i]) return SamplerKind(i);
  throw UsageError(std::string(option) + " '" + text +
                   "': expected independent, stratified, sobol or zsobol");
}

const char* sampler_name(SamplerKind kind) {
  return kNames[size_t(kind)];
}

Sampler::Sampler(SamplerKind kind, uint64_t seed, uint32_t samples_per_pixel, uint32_t domain_width,
                 uint32_t domain_height)
    : kind_(kind),
      seed_(pcg_hash(seed, 0x5eed5a3b1e7ull)),
      samples_per_pixel_(std::max(1u, samples_per_pixel)),
      grid_x_(uint32_t(std::ceil(std::sqrt(double(samples_per_pixel_))))),
      grid_y_((samples_per_pixel_ + grid_x_ - 1) / grid_x_),
      sample_bits_(ceil_log2(samples_per_pixel_)),
      pixel_bits_(ceil_log2(std::max({domain_width, domain_height, 1u}))) {}

DimensionSeed Sampler::seed(uint32_t pixel_x, uint32_t pixel_y, uint32_t dimension) const {
  DimensionSeed s;
  if (kind_ != SamplerKind::kZSobol) {
    s.key = pcg_hash(seed_, uint64_t(pixel_x) << 32 | pixel_y, dimension);
    return s;
  }
  // One scramble per dimension for the whole image: the pixels' samples are parts of one sequence.
  s.key = pcg_hash(seed_, dimension);
  const uint64_t morton = morton_2d(pixel_x, pixel_y);
  s.index_bits = permute_digits(morton, 2 * pixel_bits_, s.key) << sample_bits_;
  s.digit_key = pcg_hash(s.key, morton);
  return s;
}

uint64_t Sampler::sample_index_bits(const DimensionSeed& seed, uint32_t sample_index) const {
  return seed.index_bits | permute_digits(sample_index, sample_bits_, seed.digit_key);
}

float Sampler::get_1d(const DimensionSeed& seed, uint32_t sample_index) const {
  switch (kind_) {
    case SamplerKind::kIndependent:
      return unit_float(uint32_t(pcg_hash(seed.key, sample_index) >> 32));
    case SamplerKind::kStratified: {
      // Each round of samples_per_pixel samples is a fresh set of strata.
      const uint32_t round = sample_index / samples_per_pixel_;
      const uint64_t key = pcg_hash(seed.key, round);
      const uint32_t cell = permute(sample_index % samples_per_pixel_, samples_per_pixel_, key);
      return in_stratum(cell, samples_per_pixel_, uint32_t(pcg_hash(key, sample_index)));
    }
    case SamplerKind::kSobol: {
      const uint32_t scramble = uint32_t(seed.key);
      const uint32_t index = owen_scramble(sample_index, scramble) & 0xffffffu;  // shuffled
      return unit_float(owen_scramble(sobol(index, 0), scramble ^ 0xa511e9b3u));
    }
    case SamplerKind::kZSobol:
      return unit_float(owen_scramble(sobol(sample_index_bits(seed, sample_index), 0),
                                      uint32_t(seed.key) ^ 0xa511e9b3u));
  }
  return 0.f;
}

Vec2f Sampler::get_2d(const DimensionSeed& seed, uint32_t sample_index) const {
  switch (kind_) {
    case SamplerKind::kIndependent: {
      const uint64_t h = pcg_hash(seed.key, sample_index);
      return {unit_float(uint32_t(h >> 32)), unit_float(uint32_t(h))};
    }
    case SamplerKind::kStratified: {
      const uint32_t round = sample_index / samples_per_pixel_;
      const uint64_t key = pcg_hash(seed.key, round);
      const uint32_t cells = grid_x_ * grid_y_;
      const uint32_t cell = permute(sample_index % samples_per_pixel_, cells, key);
      const uint64_t jitter = pcg_hash(key, sample_index);
      return {in_stratum(cell % grid_x_, grid_x_, uint32_t(jitter >> 32)),
              in_stratum(cell / grid_x_, grid_y_, uint32_t(jitter))};
    }
    case SamplerKind::kSobol: {
      const uint32_t scramble = uint32_t(seed.key);
      const uint32_t index = owen_scramble(sample_index, scramble) & 0xffffffu;
      return {unit_float(owen_scramble(sobol(index, 0), scramble ^ 0xa511e9b3u)),
              unit_float(owen_scramble(sobol(index, 1), scramble ^ 0x63d83595u))};
    }
    case SamplerKind::kZSobol: {
      const uint64_t index = sample_index_bits(seed, sample_index);
      const uint32_t scramble = uint32_t(seed.key);
      return {unit_float(owen_scramble(sobol(index, 0), scramble ^ 0xa511e9b3u)),
              unit_float(owen_scramble(sobol(index, 1), scramble ^ 0x63d83595u))};
    }
  }
  return {};
}

void Sampler::fill(SampleKey& key, float* u, uint32_t count) const {
  uint32_t i = 0;
  if (count % 2 == 1) {
    u[i++] = get_1d(key);
    ++key.dimension;
  }
  for (; i + 1 < count; i += 2, key.dimension += 2) {
    const Vec2f v = get_2d(key);
    u[i] = v.x;
    u[i + 1] = v.y;
  }
}

}  // namespace fb
