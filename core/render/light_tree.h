// A bounding volume hierarchy over the lights that have a place (lamps and emissive triangles; not
// the sun or the world), which picks a light for a shading point in proportion to an estimate of
// what each brings there, and says for any light with what probability it would have picked it
// (pbrt 4e §12.6.3, BVHLightSampler, with its PMF() for multiple importance sampling; Cycles 3.5's
// light tree does the same, Blender 3.4's Cycles has none).
//
// The choice is exact on the sample grid: the sampler's values are multiples of 2^-24
// (plugin_abi.h), so a light is chosen by a cell of a range of whole cells, each node splitting its
// range between its children in proportion to their importance (at least one cell each while the
// range has two). A light's probability is the number of cells its leaf ends with, over 2^24: the
// very rate at which the grid's values choose it, with no rounding between what is sampled and
// what pmf() reports. A light whose share falls below one cell is not chosen at that point (and
// pmf() says 0), so BSDF sampling alone finds it there.
#pragma once

#include <cstdint>
#include <vector>

#include "core/render/light_bounds.h"

namespace fb {

class LightTree {
 public:
  // bounds[i]: light i's, empty (no intensity) for one the tree leaves out.
  explicit LightTree(const std::vector<LightBounds>& bounds);
  bool empty() const { return nodes_.empty(); }
  // The light that `cell` picks among the tree's `cells` cells starting at `first` (cell in that
  // range), seen from p, and the number of cells that picked it; false if none lights p.
  bool choose(Vec3f p, uint32_t first, uint32_t cells, uint32_t cell, uint32_t& light,
              uint32_t& light_cells) const;
  // The number of those cells that would pick `light` from p (0 if the tree leaves it out).
  uint32_t cells_of(Vec3f p, uint32_t first, uint32_t cells, uint32_t light) const;
  size_t node_count() const { return nodes_.size(); }
  uint32_t depth() const { return depth_; }

 private:
  struct Node {
    LightBounds bounds;
    uint32_t right_or_light;  // inner: the right child (the left one follows the node); leaf: light
    bool leaf;
  };
  struct Item {
    LightBounds bounds;
    uint32_t light;
  };
  // The path from the root to a light's leaf: bit k set where it turns right at depth k.
  struct Trail {
    uint64_t turns = 0;
    uint32_t depth = 0;
    bool in_tree = false;
  };
  static constexpr uint32_t kMaxDepth = 64;
  uint32_t build(std::vector<Item>& items, size_t begin, size_t end, Trail trail);
  // The split of [begin, end) by the surface-area-orientation heuristic (pbrt 4e §12.6.3, 12
  // buckets per axis), else by count; returns the first item of the right half.
  static size_t split(std::vector<Item>& items, size_t begin, size_t end, uint32_t depth);
  // One descent for both choose() (trail null: the cell decides) and cells_of() (the trail
  // decides), so that both do the same arithmetic.
  bool descend(Vec3f p, uint32_t first, uint32_t cells, uint32_t cell, const Trail* trail,
               uint32_t& light, uint32_t& light_cells) const;

  std::vector<Node> nodes_;
  std::vector<Trail> trails_;  // per light
  uint32_t depth_ = 0;
};

}  // namespace fb
