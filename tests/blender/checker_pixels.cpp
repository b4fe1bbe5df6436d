#include "tests/blender/checker_pixels.h"

namespace fb::test {

Square classify(const Image& image, uint32_t x, uint32_t y) {
  const double r = image.at(x, y, 0), g = image.at(x, y, 1);
  if (!(r > 0)) return Square::kEdge;
  const double ratio = g / r;
  return ratio < 0.3 ? Square::kRed : ratio > 0.6 ? Square::kWhite : Square::kEdge;
}

CheckerAgreement compare_checkers(const Image& reference, const Image& other) {
  CheckerAgreement out;
  for (uint32_t y = 0; y < reference.height; ++y)
    for (uint32_t x = 0; x < reference.width; ++x) {
      const Square a = classify(reference, x, y), b = classify(other, x, y);
      out.misplaced +=
          (a == Square::kRed && b == Square::kWhite) || (a == Square::kWhite && b == Square::kRed);
      out.edge_moved += (a == Square::kEdge) != (b == Square::kEdge);
      out.red += a == Square::kRed;
    }
  return out;
}

}  // namespace fb::test
