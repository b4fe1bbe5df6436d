// Large zero-filled arrays straight from the kernel, for the film's per-pixel sums.
//
// Anonymous pages read as zero until first written (mmap(2)), so a film needs no zeroing pass of
// its own: each page is zeroed by the kernel when the thread that renders its tile first writes
// it, in parallel and while it is in that core's cache. Transparent huge pages are asked for
// (madvise(MADV_HUGEPAGE): honoured in the kernel's THP modes "madvise" and "always"), so that a
// 1024 x 1024 film takes about 50 page faults instead of about 24,000: a fault costs about 2.5 us
// in a KVM guest, which at 1 spp weighed as much as tracing the image (docs/benchmarks.md, "Primary
// rays").
#pragma once

#include <cstddef>
#include <utility>

namespace fb {

class ZeroedPages {
 public:
  ZeroedPages() = default;
  explicit ZeroedPages(size_t bytes);  // throws std::bad_alloc when the kernel refuses
  ~ZeroedPages();
  ZeroedPages(ZeroedPages&& other) noexcept
      : mapping_(std::exchange(other.mapping_, nullptr)),
        mapped_bytes_(std::exchange(other.mapped_bytes_, 0)),
        data_(std::exchange(other.data_, nullptr)) {}
  ZeroedPages& operator=(ZeroedPages&& other) noexcept {
    std::swap(mapping_, other.mapping_);
    std::swap(mapped_bytes_, other.mapped_bytes_);
    std::swap(data_, other.data_);
    return *this;
  }

  void* data() const { return data_; }

 private:
  void* mapping_ = nullptr;  // what mmap returned, and its length, for munmap
  size_t mapped_bytes_ = 0;
  void* data_ = nullptr;
};

// `count` values of T, all zero bits (0.0 for double, 0 for integers).
template <typename T>
class ZeroedArray {
 public:
  explicit ZeroedArray(size_t count) : pages_(count * sizeof(T)) {}
  T* get() const { return static_cast<T*>(pages_.data()); }
  T& operator[](size_t i) const { return get()[i]; }

 private:
  ZeroedPages pages_;
};

// Asks the kernel to back [data, data + bytes) with transparent huge pages where it can (the
// 2 MiB-aligned part): fewer page faults on first touch. Only a hint; harmless when refused.
void advise_huge_pages(void* data, size_t bytes);

}  // namespace fb
