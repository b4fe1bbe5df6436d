#include "core/util/malloc_tuning.h"

#include <malloc.h>

namespace fb {

// glibc raises its mmap threshold (up to 32 MiB) each time a block above it is freed, so that
// after the first image or film is freed, later ones come from the heap and stay resident after
// they are freed: a few MiB per render on small shots. Setting the threshold turns that
// adjustment off. 128 KiB is glibc's own starting value: images and films (a 480 × 270 colour
// image is 1.5 MiB) are then always mapped and unmapped, while the many small allocations of
// import and rendering stay in the heap. Setting it also stops the trim threshold's adjustment
// (mallopt(3)), so freed heap tops above 128 KiB are returned too.
constexpr int kFixedMmapThresholdBytes = 128 * 1024;

void keep_large_allocations_in_mmap() {
  mallopt(M_MMAP_THRESHOLD, kFixedMmapThresholdBytes);
}

}  // namespace fb
