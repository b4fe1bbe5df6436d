#include "core/film/zeroed_pages.h"

#include <sys/mman.h>

#include <cstdint>
#include <new>

namespace fb {
namespace {
constexpr uintptr_t kHugePageBytes = uintptr_t(2) << 20;  // x86-64's PMD-sized page
}  // namespace

void advise_huge_pages(void* data, size_t bytes) {
  const uintptr_t begin = (uintptr_t(data) + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const uintptr_t end = (uintptr_t(data) + bytes) & ~(kHugePageBytes - 1);
  if (begin < end) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

// Arrays of a huge page or more are mapped one huge page longer and start on a huge-page
// boundary, so that none of their pages is left small at the ends; the spare part is never
// touched, so it takes no memory.
ZeroedPages::ZeroedPages(size_t bytes) {
  if (bytes == 0) return;
  const size_t spare = bytes >= kHugePageBytes ? kHugePageBytes : 0;
  void* p =
      mmap(nullptr, bytes + spare, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  mapping_ = p;
  mapped_bytes_ = bytes + spare;
  data_ = reinterpret_cast<void*>(spare ? (uintptr_t(p) + spare - 1) & ~(spare - 1) : uintptr_t(p));
  advise_huge_pages(data_, bytes);
}

ZeroedPages::~ZeroedPages() {
  if (mapping_) munmap(mapping_, mapped_bytes_);
}

}  // namespace fb
