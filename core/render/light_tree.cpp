#include "core/render/light_tree.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

namespace fb {

LightTree::LightTree(const std::vector<LightBounds>& bounds) : trails_(bounds.size()) {
  std::vector<Item> items;
  for (size_t i = 0; i < bounds.size(); ++i)
    if (!bounds[i].empty()) items.push_back({bounds[i], uint32_t(i)});
  if (items.empty()) return;
  nodes_.reserve(2 * items.size() - 1);
  build(items, 0, items.size(), Trail{});
}

uint32_t LightTree::build(std::vector<Item>& items, size_t begin, size_t end, Trail trail) {
  const uint32_t index = uint32_t(nodes_.size());
  depth_ = std::max(depth_, trail.depth);
  if (end - begin == 1) {
    nodes_.push_back({items[begin].bounds, items[begin].light, true});
    trail.in_tree = true;
    trails_[items[begin].light] = trail;
    return index;
  }
  LightBounds bounds;
  for (size_t i = begin; i < end; ++i)
    bounds = union_of(bounds, items[i].bounds);
  nodes_.push_back({bounds, 0, false});
  const size_t middle = split(items, begin, end, trail.depth);
  Trail left = trail, right = trail;
  ++left.depth, ++right.depth;
  right.turns |= uint64_t(1) << trail.depth;
  build(items, begin, middle, left);
  const uint32_t right_index = build(items, middle, end, right);
  nodes_[index].right_or_light = right_index;
  return index;
}

size_t LightTree::split(std::vector<Item>& items, size_t begin, size_t end, uint32_t depth) {
  const auto by_count = [&] {
    // Halves by count along the centroids' longest extent: the depth then grows as log2 of the
    // count, which keeps every trail within kMaxDepth (2^24 lights at most, LightSampler).
    Vec3f lo{HUGE_VALF, HUGE_VALF, HUGE_VALF}, hi = -lo;
    for (size_t i = begin; i < end; ++i)
      lo = min(lo, items[i].bounds.centre()), hi = max(hi, items[i].bounds.centre());
    const Vec3f extent = hi - lo;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const size_t middle = begin + (end - begin) / 2;
    std::nth_element(items.begin() + begin, items.begin() + middle, items.begin() + end,
                     [axis](const Item& a, const Item& b) {
                       return a.bounds.centre()[axis] < b.bounds.centre()[axis];
                     });
    return middle;
  };
  if (depth >= kMaxDepth / 2) return by_count();
  constexpr int kBuckets = 12;
  Vec3f lo{HUGE_VALF, HUGE_VALF, HUGE_VALF}, hi = -lo;
  LightBounds node;
  for (size_t i = begin; i < end; ++i) {
    lo = min(lo, items[i].bounds.centre()), hi = max(hi, items[i].bounds.centre());
    node = union_of(node, items[i].bounds);
  }
  const auto bucket_of = [&](const Item& item, int axis) {
    const float extent = hi[axis] - lo[axis];
    const int b = int(float(kBuckets) * (item.bounds.centre()[axis] - lo[axis]) / extent);
    return std::clamp(b, 0, kBuckets - 1);
  };
  float best_cost = HUGE_VALF;
  int best_axis = -1, best_bucket = -1;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(hi[axis] > lo[axis])) continue;
    std::array<LightBounds, kBuckets> buckets;
    for (size_t i = begin; i < end; ++i) {
      LightBounds& b = buckets[size_t(bucket_of(items[i], axis))];
      b = union_of(b, items[i].bounds);
    }
    for (int s = 0; s < kBuckets - 1; ++s) {
      LightBounds below, above;
      for (int b = 0; b <= s; ++b)
        below = union_of(below, buckets[size_t(b)]);
      for (int b = s + 1; b < kBuckets; ++b)
        above = union_of(above, buckets[size_t(b)]);
      if (below.empty() || above.empty()) continue;
      const float cost = orientation_cost(below, axis) + orientation_cost(above, axis);
      if (cost < best_cost) best_cost = cost, best_axis = axis, best_bucket = s;
    }
  }
  if (best_axis < 0) return by_count();
  const auto middle =
      std::partition(items.begin() + begin, items.begin() + end,
                     [&](const Item& i) { return bucket_of(i, best_axis) <= best_bucket; });
  const size_t m = size_t(middle - items.begin());
  return m == begin || m == end ? by_count() : m;
}

bool LightTree::descend(Vec3f p, uint32_t first, uint32_t cells, uint32_t cell, const Trail* trail,
                        uint32_t& light, uint32_t& light_cells) const {
  if (nodes_.empty()) return false;
  const auto finite_importance = [&](const Node& n) {
    return std::min(importance(n.bounds, p), FLT_MAX);  // infinity would spoil the ratio
  };
  uint32_t at = 0, depth = 0;
  while (!nodes_[at].leaf) {
    const uint32_t left = at + 1, right = nodes_[at].right_or_light;
    const double i_left = finite_importance(nodes_[left]);
    const double i_right = finite_importance(nodes_[right]);
    if (!(i_left > 0) && !(i_right > 0)) return false;
    // The left child's cells: its share of the range, at least one for each child that brings
    // light while there are two to share.
    uint32_t left_cells;
    if (!(i_right > 0))
      left_cells = cells;
    else if (!(i_left > 0))
      left_cells = 0;
    else if (cells < 2)
      left_cells = i_left >= i_right ? cells : 0;
    else
      left_cells = uint32_t(std::clamp<double>(std::llround(i_left / (i_left + i_right) * cells),
                                               1.0, double(cells - 1)));
    const bool go_right = trail ? ((trail->turns >> depth) & 1) != 0 : cell >= first + left_cells;
    if (go_right) {
      first += left_cells;
      cells -= left_cells;
      at = right;
    } else {
      cells = left_cells;
      at = left;
    }
    if (cells == 0) return false;
    ++depth;
  }
  light = nodes_[at].right_or_light;
  light_cells = cells;
  return true;
}

bool LightTree::choose(Vec3f p, uint32_t first, uint32_t cells, uint32_t cell, uint32_t& light,
                       uint32_t& light_cells) const {
  return descend(p, first, cells, cell, nullptr, light, light_cells);
}

uint32_t LightTree::cells_of(Vec3f p, uint32_t first, uint32_t cells, uint32_t light) const {
  if (light >= trails_.size() || !trails_[light].in_tree) return 0;
  uint32_t reached, light_cells;
  if (!descend(p, first, cells, 0, &trails_[light], reached, light_cells)) return 0;
  return light_cells;
}

}  // namespace fb
