// Which light next-event estimation samples from a shading point, and with what probability any
// light would have been chosen there (for multiple importance sampling). Two ways:
// - by power: each light in proportion to its estimated power, wherever the point is (pbrt 4e
//   §12.6.2, PowerLightSampler);
// - by a light tree (core/render/light_tree.h): the lights that have a place by what each is
//   estimated to bring to the point, the sun and the world beside the tree by power, as pbrt 4e's
//   BVHLightSampler keeps its infinite lights out of its tree.
// Either way the choice is exact on the sample grid (values of u are multiples of 2^-24,
// plugin_abi.h): a light's probability is the share of the 2^24 cells that choose it.
#pragma once

#include <cstdint>
#include <vector>

#include "core/render/light_bounds.h"
#include "core/render/light_tree.h"

namespace fb {

enum class LightSelection {
  kAuto,   // the tree from kTreeFromLights lights with a place on (docs/benchmarks.md)
  kPower,  // by power
  kTree,   // by the light tree
};

class LightChoice {
 public:
  // The tree's threshold, chosen by measurement (docs/benchmarks.md, "Light sampling").
  static constexpr size_t kTreeFromLights = 8;
  static constexpr uint32_t kCells = 1u << 24;
  // With the tree, the share of a light's choices still made by power wherever the point is (a
  // defensive mixture, Hesterberg 1995): the tree's estimate can be far too low for a light near
  // the point in a node whose centre is far, and the mixture bounds the weight a sample can take
  // to 1 / kPowerShare of power sampling's.
  static constexpr double kPowerShare = 0.1;

  LightChoice() = default;
  // Per light: its estimated power (0: never chosen) and its bounds (empty for a light without a
  // place: a sun, the world). Throws InputError for more lights than the cells tell apart.
  LightChoice(const std::vector<double>& power, const std::vector<LightBounds>& bounds,
              LightSelection selection);
  bool empty() const { return first_cell_.empty(); }
  bool uses_tree() const { return !tree_.empty(); }
  // The light u picks for the point p, and its probability; false if none lights p.
  bool choose(Vec3f p, float u, uint32_t& light, float& pmf) const;
  // The probability that choose() picks `light` for p.
  float pmf(Vec3f p, uint32_t light) const;

 private:
  static constexpr uint32_t kNotChosen = UINT32_MAX, kTreeEntry = UINT32_MAX;
  // Cells per entry: a whole number of the 2^24, at least one for each that carries power.
  void build_cells(const std::vector<double>& power);
  std::vector<uint32_t> entry_light_;  // per entry: its light, or kTreeEntry
  std::vector<uint32_t> light_entry_;  // per light: its own entry, or kNotChosen
  std::vector<uint32_t> first_cell_;   // per entry, and the total (2^24) at the end
  LightTree tree_{{}};
};

}  // namespace fb
