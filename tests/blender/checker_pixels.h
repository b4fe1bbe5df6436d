// Where a red and white checker texture lands, pixel by pixel, in two renders of one shot
// (material_shot.py's checker): the shots that texture objects share this classification.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/image/image.h"

namespace fb::test {

// By chromaticity, G/R: the red squares ~0.02, white ones (and anything grey or gold) above 0.6;
// between the two, and black, is an edge.
enum class Square { kRed, kWhite, kEdge };
Square classify(const Image& image, uint32_t x, uint32_t y);

struct CheckerAgreement {
  size_t misplaced = 0;   // red in one image and white in the other
  size_t edge_moved = 0;  // an edge in one image only
  size_t red = 0;         // red in the reference: how much of the checker is in view
};

// `reference` and `other` of the same size.
CheckerAgreement compare_checkers(const Image& reference, const Image& other);

}  // namespace fb::test
