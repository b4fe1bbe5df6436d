// Sample values for the render loop and the integrators. Every value is a function of (seed,
// pixel, sample index, dimension) and nothing else, so an image is identical for any thread count
// or tile order (docs/conventions.md), and lies on the 2^-24 grid the plugin ABI promises.
//
// Dimensions are spent as 1-D values and 2-D pairs: the filter offset (0, 1), the lens point
// (2, 3), the time (4), then the integrator's requests (fb_scene_api.next_samples), each taken as
// one 1-D value when its count is odd and then pairs, so a path's light choice and light point,
// or its lobe choice and direction, get one 1-D and one 2-D stratum (docs/sampling.md). Every
// pair is stratified on its own and decorrelated from the others by its own scramble ("padding",
// Kollig and Keller 2002), so every dimension, not only the first few, is well stratified.
//
// The kinds (docs/sampling.md has the measured errors):
//   independent  uniform values: a PCG hash of the key (core/math/random.h);
//   stratified   jittered strata: N samples of a pixel fill N of the cells of the most nearly
//                square grid with at least N cells, each cell at most once, in random order;
//   sobol        Owen-scrambled Sobol (0,2)-sequences per pixel and pair, their order shuffled
//                (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)): 2^k samples of
//                a pixel form a (0,k,2)-net in every pair;
//   zsobol       the same points, but one Sobol sequence for the whole image in Morton order of the
//                pixels with randomly permuted base-4 digits (Ahmed and Wonka 2020, "Screen-Space
//                Blue-Noise Diffusion of Monte Carlo Sampling Error via Hierarchical Ordering of
//                Pixels"; pbrt-v4's ZSobolSampler): neighbouring pixels' errors are
//                anti-correlated, so the error is blue noise across the image.
#pragma once

#include <cstdint>
#include <string>

#include <filmback/vec.h>

#include "core/math/low_discrepancy.h"

namespace fb {

enum class SamplerKind : uint8_t { kIndependent, kStratified, kSobol, kZSobol };
constexpr SamplerKind kDefaultSampler = SamplerKind::kSobol;

// "independent", "stratified", "sobol", "zsobol"; a UsageError naming `option` otherwise.
SamplerKind parse_sampler_kind(const std::string& text, const char* option);
const char* sampler_name(SamplerKind kind);

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

// What every sample of one pixel shares in one dimension (or pair): hashed once per pixel.
struct DimensionSeed {
  uint64_t key = 0;         // the pixel's and dimension's hash (all kinds)
  uint64_t index_bits = 0;  // zsobol: the pixel's digits of the image-wide index, permuted
  uint64_t digit_key = 0;   // zsobol: seeds the permutations of the sample's own digits
};

class Sampler {
 public:
  // `samples_per_pixel` is the count each pixel will take (stratified sizes its strata by it,
  // zsobol its digits); `domain_width`/`height` the pixels sampled (zsobol's Morton order).
  Sampler(SamplerKind kind, uint64_t seed, uint32_t samples_per_pixel, uint32_t domain_width,
          uint32_t domain_height);

  SamplerKind kind() const { return kind_; }

  DimensionSeed seed(uint32_t pixel_x, uint32_t pixel_y, uint32_t dimension) const;
  float get_1d(const DimensionSeed& seed, uint32_t sample_index) const;
  Vec2f get_2d(const DimensionSeed& seed, uint32_t sample_index) const;

  float get_1d(const SampleKey& key) const {
    return get_1d(seed(key.pixel_x, key.pixel_y, key.dimension), key.sample_index);
  }
  Vec2f get_2d(const SampleKey& key) const {
    return get_2d(seed(key.pixel_x, key.pixel_y, key.dimension), key.sample_index);
  }

  // The next `count` values of a path (fb_scene_api.next_samples): when `count` is odd the first
  // is a 1-D value, the rest are 2-D pairs; key.dimension moves past them.
  void fill(SampleKey& key, float* u, uint32_t count) const;

 private:
  uint64_t sample_index_bits(const DimensionSeed& seed, uint32_t sample_index) const;

  SamplerKind kind_;
  uint64_t seed_;
  uint32_t samples_per_pixel_;
  uint32_t grid_x_, grid_y_;  // stratified: the 2-D grid, grid_x_ * grid_y_ >= samples
  uint32_t sample_bits_;      // zsobol: ceil(log2(samples per pixel))
  uint32_t pixel_bits_;       // zsobol: ceil(log2(the longer domain side))
};

}  // namespace fb
