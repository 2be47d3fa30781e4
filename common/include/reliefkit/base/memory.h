// ReliefKit — large arrays backed by transparent huge pages.
//
// Cores fill arrays of tens to hundreds of MiB. With 4 KiB pages, the first touch of each page
// is a page fault, and on virtual machines these faults cost up to a fifth of a curvature
// computation. `sized` reserves the vector's memory, asks the kernel for 2 MiB pages on it
// (madvise, effective where transparent huge pages are in "madvise" or "always" mode), and only
// then writes it. Small arrays are left alone.
//
// `RetainedMemory` keeps, for the duration of one run, the blocks a stage frees for the next
// stage to reuse (see below).
#pragma once

#include <malloc.h>
#include <sys/mman.h>

#include <atomic>

#include <cstdint>
#include <vector>

namespace reliefkit {

inline void advise_huge_pages(void* data, size_t bytes) {
#ifdef MADV_HUGEPAGE
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  if (bytes < 2 * kHuge) return;
  uintptr_t b = (reinterpret_cast<uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  uintptr_t e = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (e > b) madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

/// v = n copies of `value`, with huge pages advised before the memory is first written.
template <class T>
void sized(std::vector<T>& v, size_t n, const T& value = T()) {
  std::vector<T>().swap(v);
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
  v.assign(n, value);
}

/// While alive (one per filter run; nested ones do nothing more): blocks of up to 32 MiB come from
/// malloc's heap and freed ones stay there, so a stage reuses the memory the previous one freed
/// instead of the kernel unmapping it and faulting fresh zeroed pages in again; on destruction the
/// settings go back to glibc's defaults and the free memory is returned to the system
/// (malloc_trim). On a virtual machine a page fault costs several microseconds: measured with
/// Relief Edges' base-normal solve on 1 M faces, about a third of its time (docs/benchmarks.md).
class RetainedMemory {
 public:
  RetainedMemory() {
    if (depth().fetch_add(1) > 0) return;
    mallopt(M_MMAP_THRESHOLD, kLargestHeapBlock);
    mallopt(M_TRIM_THRESHOLD, kKeptWhileRunning);
    mallopt(M_TOP_PAD, kHeapGrowth);
  }
  ~RetainedMemory() {
    if (depth().fetch_sub(1) > 1) return;
    mallopt(M_MMAP_THRESHOLD, kDefaultThreshold);
    mallopt(M_TRIM_THRESHOLD, kDefaultThreshold);
    mallopt(M_TOP_PAD, 0);
    malloc_trim(0);
  }
  RetainedMemory(const RetainedMemory&) = delete;
  RetainedMemory& operator=(const RetainedMemory&) = delete;

 private:
  static constexpr int kLargestHeapBlock = 32 << 20;    // glibc's upper limit for the threshold
  static constexpr int kKeptWhileRunning = 1 << 30;     // free memory kept at the heap's top
  static constexpr int kHeapGrowth = 64 << 20;          // the heap grows in steps of this much
  static constexpr int kDefaultThreshold = 128 << 10;   // glibc's default mmap and trim thresholds
  static std::atomic<int>& depth() {
    static std::atomic<int> d{0};
    return d;
  }
};

}  // namespace reliefkit
