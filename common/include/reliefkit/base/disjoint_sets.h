// ReliefKit — disjoint sets (union-find) united from every core at once.
#pragma once

#include <utility>
#include <vector>

#include "reliefkit/base/memory.h"

namespace reliefkit {

/// Disjoint sets of 0 .. n-1 that any number of threads unite at once, without locks: a root is
/// only ever linked under a lower one (compare-and-swap), so each set's root is its lowest element
/// whatever the threads' timing, and the result is the same on any number of cores.
class DisjointSets {
 public:
  explicit DisjointSets(int n) {
    sized(parent_, size_t(n));
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) parent_[size_t(i)] = i;
  }

  /// The root of x's set (path halving: every pointer still leads to an ancestor).
  int find(int x) {
    int* p = parent_.data();
    for (;;) {
      const int up = __atomic_load_n(&p[x], __ATOMIC_RELAXED);
      if (up == x) return x;
      const int upup = __atomic_load_n(&p[up], __ATOMIC_RELAXED);
      if (upup != up) __atomic_store_n(&p[x], upup, __ATOMIC_RELAXED);
      x = upup;
    }
  }

  void unite(int a, int b) {
    for (a = find(a), b = find(b); a != b; a = find(a), b = find(b)) {
      if (a < b) std::swap(a, b);
      if (__atomic_compare_exchange_n(&parent_[size_t(a)], &a, b, false, __ATOMIC_ACQ_REL, __ATOMIC_RELAXED)) return;
    }
  }

  /// Each element's set as an index 0, 1, ... in the order of the sets' lowest elements (`count`:
  /// how many sets). Called once all unions are done; the sets are used up. Every pointer leads
  /// to a lower element, so one pass upwards points each element at its root, and a second numbers
  /// the roots and copies each root's number to its set.
  std::vector<int> numbered(int& count) && {
    std::vector<int>& p = parent_;
    for (size_t i = 0; i < p.size(); ++i) p[i] = p[size_t(p[i])];
    count = 0;
    for (size_t i = 0; i < p.size(); ++i) p[i] = p[i] == int(i) ? count++ : p[size_t(p[i])];
    return std::move(p);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace reliefkit
