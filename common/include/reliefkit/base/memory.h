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
#include <omp.h>
#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>

#include <cstdint>
#include <type_traits>
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

namespace detail {
template <class T, class = void>
struct ZeroOf {
  static T get() { return T(); }
};
template <class T>
struct ZeroOf<T, std::enable_if_t<(T::SizeAtCompileTime > 0)>> {  // Eigen's fixed-size matrices
  static T get() { return T(T::Zero()); }
};
}  // namespace detail

/// T's zero: T::Zero() for Eigen's fixed-size matrices (whose T() leaves the values undefined:
/// an array of them filled with T() held copies of whatever was on the stack), else T().
template <class T>
T zero_of() {
  return detail::ZeroOf<T>::get();
}

/// v = n copies of `value`, with huge pages advised before the memory is first written.
template <class T>
void sized(std::vector<T>& v, size_t n, const T& value = zero_of<T>()) {
  std::vector<T>().swap(v);
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
  v.assign(n, value);
}

/// One array of n copies of `value` per OpenMP thread, all made by the calling thread (its heap,
/// huge pages advised), for a parallel region to take its own by omp_get_thread_num(). An array a
/// worker thread makes comes from that thread's own malloc arena, where pages are faulted 4 KiB
/// at a time.
template <class T>
std::vector<std::vector<T>> per_thread(size_t n, const T& value) {
  std::vector<std::vector<T>> arrays(static_cast<size_t>(omp_get_max_threads()));
  for (auto& a : arrays) sized(a, n, value);
  return arrays;
}

/// While alive (one per filter run; nested ones do nothing more): blocks of up to 32 MiB come from
/// malloc's heap and freed ones stay there, so a stage reuses the memory the previous one freed
/// instead of the kernel unmapping it and faulting fresh zeroed pages in again; on destruction the
/// settings go back to glibc's defaults and the free memory is returned to the system
/// (malloc_trim). On a virtual machine a page fault costs several microseconds: measured with
/// Relief Edges' base-normal solve on 1 M faces, about a third of its time (docs/benchmarks.md).
///
/// `expected_bytes` (about what the run will allocate, at most 1 GiB is used) is taken from the
/// heap at once and given back to it with huge pages advised on the whole range: nothing is
/// touched, but every block later carved from it is faulted in 2 MiB at a time instead of 4 KiB
/// (docs/benchmarks.md: the curvature filter's copy stage on 1 M faces 0.17-0.26 s -> 0.09-0.13 s).
class RetainedMemory {
 public:
  explicit RetainedMemory(size_t expected_bytes = 0) {
    if (depth().fetch_add(1) > 0) return;
    mallopt(M_MMAP_THRESHOLD, kLargestHeapBlock);
    mallopt(M_TRIM_THRESHOLD, kKeptWhileRunning);
    mallopt(M_TOP_PAD, kHeapGrowth);
    reserve_huge_heap(std::min(expected_bytes, size_t(kKeptWhileRunning)));
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
  // Grows the heap by `bytes` in blocks just under the mmap threshold, advises huge pages on the
  // span they cover (when they are one span, as on a heap with nothing free inside) and frees
  // them, newest first, so they merge back into the heap's free top.
  static void reserve_huge_heap(size_t bytes) {
    constexpr size_t kBlock = size_t(kLargestHeapBlock) / 2;
    std::vector<char*> blocks;
    for (size_t got = 0; got < bytes; got += kBlock) {
      char* b = static_cast<char*>(std::malloc(kBlock));
      if (!b) break;
      blocks.push_back(b);
    }
    if (!blocks.empty()) {
      const auto [lo, hi] = std::minmax_element(blocks.begin(), blocks.end());
      const size_t span = size_t(*hi - *lo) + kBlock;
      if (span <= 2 * blocks.size() * kBlock) advise_huge_pages(*lo, span);
    }
    for (size_t i = blocks.size(); i-- > 0;) std::free(blocks[i]);
  }
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
