// ReliefKit — sums over many rows on every core that come out the same on any number of cores.
#pragma once

#include <algorithm>
#include <vector>

namespace reliefkit {

/// Rows per partial sum: the partial sums and the order they are added in do not depend on the
/// number of threads, so neither does the result (a solver's iterations are reproducible).
constexpr int kReductionBlock = 4096;

/// Σ term(i) over i in [0, n), summed block by block (`zero`: the sum's zero; T needs +=: a
/// double, or an Eigen vector to sum several quantities in one pass).
template <class T, class Term>
T blocked_sum(int n, const T& zero, Term term) {
  const int blocks = (n + kReductionBlock - 1) / kReductionBlock;
  std::vector<T> partial(static_cast<size_t>(blocks), zero);
#pragma omp parallel for schedule(static)
  for (int b = 0; b < blocks; ++b) {
    T sum = zero;
    for (int i = b * kReductionBlock; i < std::min(n, (b + 1) * kReductionBlock); ++i) sum += term(i);
    partial[size_t(b)] = sum;
  }
  T total = zero;
  for (const T& p : partial) total += p;
  return total;
}

}  // namespace reliefkit
