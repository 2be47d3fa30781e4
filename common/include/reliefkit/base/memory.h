// ReliefKit — large arrays backed by transparent huge pages.
//
// Cores fill arrays of tens to hundreds of MiB. With 4 KiB pages, the first touch of each page
// is a page fault, and on virtual machines these faults cost up to a fifth of a curvature
// computation. `sized` reserves the vector's memory, asks the kernel for 2 MiB pages on it
// (madvise, effective where transparent huge pages are in "madvise" or "always" mode), and only
// then writes it. Small arrays are left alone.
#pragma once

#include <sys/mman.h>

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

}  // namespace reliefkit
