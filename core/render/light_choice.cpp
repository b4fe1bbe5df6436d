#include "core/render/light_choice.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/util/error.h"

namespace fb {

LightChoice::LightChoice(const std::vector<double>& power, const std::vector<LightBounds>& bounds,
                         LightSelection selection)
    : light_entry_(power.size(), kNotChosen) {
  size_t placed = 0;
  for (size_t i = 0; i < power.size(); ++i)
    if (power[i] > 0 && !bounds[i].empty()) ++placed;
  const bool tree = selection == LightSelection::kTree ||
                    (selection == LightSelection::kAuto && placed >= kTreeFromLights);
  std::vector<double> entry_power;
  double tree_power = 0;
  std::vector<LightBounds> tree_bounds(power.size());
  for (size_t i = 0; i < power.size(); ++i) {
    if (!(power[i] > 0)) continue;
    double own = power[i];
    if (tree && !bounds[i].empty()) {
      tree_bounds[i] = bounds[i];
      tree_power += (1 - kPowerShare) * power[i];
      own = kPowerShare * power[i];
    }
    if (!(own > 0)) continue;
    light_entry_[i] = uint32_t(entry_light_.size());
    entry_light_.push_back(uint32_t(i));
    entry_power.push_back(own);
  }
  if (tree_power > 0) {
    // The tree as one entry, with the power of its lights, beside the lights without a place.
    entry_light_.push_back(kTreeEntry);
    entry_power.push_back(tree_power);
    tree_ = LightTree(tree_bounds);
  }
  build_cells(entry_power);
}

// Each entry gets a whole number of the 2^24 cells, at least one if it carries any power, and its
// probability is exactly its share of cells. An entry with a smaller share than one cell would
// otherwise be chosen never, or at the wrong rate, depending on its place in the list.
void LightChoice::build_cells(const std::vector<double>& power) {
  double total = 0;
  for (double p : power)
    total += p;
  if (!(total > 0) || !std::isfinite(total)) {  // no light carries energy: never sampled
    std::fill(light_entry_.begin(), light_entry_.end(), kNotChosen);
    return;
  }
  if (power.size() > kCells)
    throw InputError("the scene has " + std::to_string(power.size()) +
                     " emitting lights and triangles, more than the " + std::to_string(kCells) +
                     " that light selection can tell apart");
  std::vector<uint32_t> cells(power.size(), 0);
  int64_t assigned = 0;
  for (size_t i = 0; i < power.size(); ++i)
    assigned += cells[i] = std::max<uint32_t>(1, uint32_t(std::llround(power[i] / total * kCells)));
  // Settle rounding on the entries with the most cells, never taking one below a single cell.
  std::vector<size_t> order(power.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cells[a] > cells[b]; });
  for (size_t k = 0; assigned != kCells; k = (k + 1) % order.size()) {
    uint32_t& c = cells[order[k]];
    if (assigned < kCells) {
      c += uint32_t(kCells - assigned);
      assigned = kCells;
    } else if (c > 1) {
      const uint32_t take = uint32_t(std::min<int64_t>(assigned - kCells, c - 1));
      c -= take;
      assigned -= take;
    }
  }
  first_cell_.assign(1, 0);
  for (uint32_t c : cells)
    first_cell_.push_back(first_cell_.back() + c);
}

bool LightChoice::choose(Vec3f p, float u, uint32_t& light, float& pmf) const {
  if (empty()) return false;
  const uint32_t cell = std::min(uint32_t(u * float(kCells)), kCells - 1);
  const size_t entry =
      size_t(std::upper_bound(first_cell_.begin(), first_cell_.end(), cell) - first_cell_.begin()) -
      1;
  if (entry_light_[entry] != kTreeEntry) {
    light = entry_light_[entry];
    pmf = this->pmf(p, light);  // its own cells and the tree's, if it is in the tree
    return true;
  }
  const uint32_t first = first_cell_[entry];
  uint32_t cells;
  if (!tree_.choose(p, first, kCells - first, cell, light, cells)) return false;
  // Its cells in the tree from this point, and its own by power (pmf() without a second descent).
  const uint32_t own = light_entry_[light];
  if (own != kNotChosen) cells += first_cell_[own + 1] - first_cell_[own];
  pmf = float(cells) / float(kCells);
  return true;
}

float LightChoice::pmf(Vec3f p, uint32_t light) const {
  if (empty() || light >= light_entry_.size()) return 0.f;
  const uint32_t entry = light_entry_[light];
  uint32_t cells = entry == kNotChosen ? 0 : first_cell_[entry + 1] - first_cell_[entry];
  if (uses_tree()) {
    const uint32_t first = first_cell_[entry_light_.size() - 1];  // the tree's entry is the last
    cells += tree_.cells_of(p, first, kCells - first, light);
  }
  return float(cells) / float(kCells);  // exact: at most 2^24
}

}  // namespace fb
