#include "core/film/part_coverage.h"

#include <algorithm>
#include <cstdint>

namespace fb {

std::optional<CoverageProblem> check_coverage(const std::vector<PixelRect>& parts, uint32_t width,
                                              uint32_t height) {
  // The frame cut at every part edge into cells, each wholly inside or outside each part.
  std::vector<uint32_t> xs{0, width}, ys{0, height};
  for (size_t i = 0; i < parts.size(); ++i) {
    const PixelRect& p = parts[i];
    if (p.empty() || p.x1 > width || p.y1 > height)
      return CoverageProblem{CoverageProblem::Kind::kOutside, i, 0, p};
    xs.insert(xs.end(), {p.x0, p.x1}), ys.insert(ys.end(), {p.y0, p.y1});
  }
  for (std::vector<uint32_t>* v : {&xs, &ys}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  const auto cell = [](const std::vector<uint32_t>& v, uint32_t at) {
    return size_t(std::lower_bound(v.begin(), v.end(), at) - v.begin());
  };
  const size_t cells_x = xs.size() - 1;
  // Per cell: 1 + the part that holds it, 0 for none.
  std::vector<uint32_t> owner(cells_x * (ys.size() - 1), 0);
  for (size_t i = 0; i < parts.size(); ++i) {
    const PixelRect& p = parts[i];
    for (size_t cy = cell(ys, p.y0); cy < cell(ys, p.y1); ++cy)
      for (size_t cx = cell(xs, p.x0); cx < cell(xs, p.x1); ++cx) {
        uint32_t& o = owner[cy * cells_x + cx];
        if (o != 0)
          return CoverageProblem{
              CoverageProblem::Kind::kOverlap, i, o - 1, {xs[cx], ys[cy], xs[cx + 1], ys[cy + 1]}};
        o = uint32_t(i + 1);
      }
  }
  for (size_t c = 0; c < owner.size(); ++c)
    if (owner[c] == 0) {
      const size_t cx = c % cells_x, cy = c / cells_x;
      return CoverageProblem{
          CoverageProblem::Kind::kGap, 0, 0, {xs[cx], ys[cy], xs[cx + 1], ys[cy + 1]}};
    }
  return std::nullopt;
}

}  // namespace fb
