#include "reliefkit/base/multilevel.h"

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <type_traits>
#include <vector>

#include "reliefkit/base/reductions.h"
#include "reliefkit/base/solvers.h"

namespace reliefkit {

namespace {

// Damping of the Jacobi steps, smoother and prolongation alike: 4 / (3 ρ(D⁻¹A)) with ρ ≤ 2 for the
// diagonally dominant M-matrices this is for (negative weights clamped) — the textbook 2/3.
constexpr double kJacobiDamping = 2.0 / 3.0;


template <typename Visit>
void for_each_neighbour(const Eigen::SparseMatrix<double>& A, int i, Visit visit) {
  for (Eigen::SparseMatrix<double>::InnerIterator it(A, i); it; ++it)
    if (int(it.row()) != i && it.value() != 0) visit(int(it.row()), it.value());
}

}  // namespace

std::vector<int> aggregate_vertices(const Eigen::SparseMatrix<double>& A, int& count) {
  const int n = int(A.rows());
  std::vector<int> aggregate(size_t(n), -1);
  count = 0;
  // A vertex whose neighbours are all free starts an aggregate with them.
  for (int i = 0; i < n; ++i) {
    if (aggregate[size_t(i)] >= 0) continue;
    bool all_free = true;
    for_each_neighbour(A, i, [&](int j, double) { all_free = all_free && aggregate[size_t(j)] < 0; });
    if (!all_free) continue;
    aggregate[size_t(i)] = count;
    for_each_neighbour(A, i, [&](int j, double) { aggregate[size_t(j)] = count; });
    ++count;
  }
  // The others join the neighbouring aggregate they are most strongly coupled to (each has one:
  // it was not free to start its own only because a neighbour was taken).
  for (int i = 0; i < n; ++i) {
    if (aggregate[size_t(i)] >= 0) continue;
    double strongest = -1;
    int best = -1;
    for_each_neighbour(A, i, [&](int j, double a) {
      if (aggregate[size_t(j)] >= 0 && std::abs(a) > strongest) strongest = std::abs(a), best = aggregate[size_t(j)];
    });
    aggregate[size_t(i)] = best >= 0 ? best : count++;
  }
  return aggregate;
}

// One level of the hierarchy: its operator (both triangles; symmetric, so its columns are its
// rows), the smoother, and the aggregates that make the next level.
struct AggregationLevel {
  int n = 0;
  const int* ptr = nullptr;  // the operator's rows
  const int* idx = nullptr;
  const double* val = nullptr;
  Eigen::SparseMatrix<double> owned;            // a coarse level's operator (the finest is the caller's)
  std::vector<double> damped_inverse_diagonal;  // ω / A_ii
  std::vector<int> aggregate;                   // the prolongation: a coarse value is copied to its aggregate
  std::vector<int> member_offset, member;       // the rows of each aggregate (the restriction's sums)
  int coarse_size = 0;
  void view(const Eigen::SparseMatrix<double>& a) {
    n = int(a.rows()), ptr = a.outerIndexPtr(), idx = a.innerIndexPtr(), val = a.valuePtr();
  }
};

struct MultilevelPreconditioner::Parts {
  std::deque<AggregationLevel> levels;  // finest first; the last one's aggregates form the factorized system
  Eigen::CholmodSimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower> coarse;
  bool ok = false;
  Parts() { use_one_blas_thread(); }
};

namespace {

using Parts = MultilevelPreconditioner::Parts;

// The rows of each aggregate, as offsets into one list.
void list_members(AggregationLevel& l) {
  l.member_offset.assign(size_t(l.coarse_size) + 1, 0);
  for (int a : l.aggregate) ++l.member_offset[size_t(a) + 1];
  for (int c = 0; c < l.coarse_size; ++c) l.member_offset[size_t(c) + 1] += l.member_offset[size_t(c)];
  l.member.resize(size_t(l.n));
  std::vector<int> next(l.member_offset.begin(), l.member_offset.end() - 1);
  for (int i = 0; i < l.n; ++i) l.member[size_t(next[size_t(l.aggregate[size_t(i)])]++)] = i;
}

// damped_inverse_diagonal = damping / A_ii (0 where A_ii is not positive).
void inverse_diagonal(AggregationLevel& l, double damping) {
  l.damped_inverse_diagonal.resize(size_t(l.n));
#pragma omp parallel for schedule(static)
  for (int i = 0; i < l.n; ++i) {
    const int *first = l.idx + l.ptr[i], *last = l.idx + l.ptr[i + 1];
    const int* at = std::lower_bound(first, last, i);
    const double d = (at != last && *at == i) ? l.val[at - l.idx] : 0.0;
    l.damped_inverse_diagonal[size_t(i)] = d > 0 ? damping / d : 0;
  }
}

// Sorts the entries of one column (from `first` to the end) by row.
void sort_column(std::vector<int>& inner, std::vector<double>& value, size_t first) {
  std::vector<std::pair<int, double>> column;
  for (size_t k = first; k < inner.size(); ++k) column.emplace_back(inner[k], value[k]);
  std::sort(column.begin(), column.end());
  for (size_t k = first; k < inner.size(); ++k) inner[k] = column[k - first].first, value[k] = column[k - first].second;
}

// Galerkin coarse operator Pᵀ A P, both triangles, rows of each column in order (as CHOLMOD and
// the next level's aggregation want them): the couplings summed aggregate by aggregate, assembled
// column by column (no triplet sort).
Eigen::SparseMatrix<double> coarse_operator(const AggregationLevel& l) {
  const int nc = l.coarse_size;
  std::vector<int> slot(size_t(nc), -1), outer(size_t(nc) + 1, 0), inner;
  std::vector<double> value;
  inner.reserve(size_t(l.ptr[l.n]) / 2);
  value.reserve(size_t(l.ptr[l.n]) / 2);
  for (int c = 0; c < nc; ++c) {
    const size_t first = inner.size();
    for (int m = l.member_offset[size_t(c)]; m < l.member_offset[size_t(c) + 1]; ++m)
      for (int e = l.ptr[l.member[size_t(m)]]; e < l.ptr[l.member[size_t(m)] + 1]; ++e) {
        const int r = l.aggregate[size_t(l.idx[e])];
        if (slot[size_t(r)] < int(first)) slot[size_t(r)] = int(inner.size()), inner.push_back(r), value.push_back(0);
        value[size_t(slot[size_t(r)])] += l.val[e];
      }
    outer[size_t(c) + 1] = int(inner.size());
    sort_column(inner, value, first);
  }
  Eigen::SparseMatrix<double> coarse(nc, nc);
  coarse.resizeNonZeros(Eigen::Index(inner.size()));
  std::copy(outer.begin(), outer.end(), coarse.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), coarse.innerIndexPtr());
  std::copy(value.begin(), value.end(), coarse.valuePtr());
  return coarse;
}

}  // namespace

MultilevelPreconditioner::MultilevelPreconditioner(const Eigen::SparseMatrix<double>& A, int largest_factorized)
    : parts_(new Parts) {
  Parts& p = *parts_;
  p.levels.emplace_back().view(A);
  const Eigen::SparseMatrix<double>* matrix = &A;
  for (;;) {
    AggregationLevel& l = p.levels.back();
    inverse_diagonal(l, kJacobiDamping);
    l.aggregate = aggregate_vertices(*matrix, l.coarse_size);
    list_members(l);
    const bool last = l.coarse_size <= largest_factorized || 2 * l.coarse_size > l.n;  // or it stopped shrinking
    if (last) break;
    AggregationLevel& next = p.levels.emplace_back();
    next.owned = coarse_operator(l);
    next.view(next.owned);
    matrix = &next.owned;
  }
  p.coarse.cholmod().print = 0;
  p.coarse.cholmod().nmethods = 1;
  p.coarse.cholmod().method[0].ordering = CHOLMOD_AMD;
  p.coarse.compute(coarse_operator(p.levels.back()));
  p.ok = p.coarse.info() == Eigen::Success;
}

MultilevelPreconditioner::~MultilevelPreconditioner() = default;
bool MultilevelPreconditioner::ok() const { return parts_->ok; }
int MultilevelPreconditioner::coarse_size() const { return parts_->levels.back().coarse_size; }
int MultilevelPreconditioner::levels() const { return int(parts_->levels.size()) + 1; }

namespace {

// Blocks of K columns stored row by row (the K values of a row side by side): the sparse products
// then read each neighbour's values from one cache line. Buffers are allocated once per solve.
using Rows = std::vector<double>;

// Per column, Σ_i a_i b_i (reproducible whatever the number of threads: reductions.h).
template <int K>
std::array<double, K> column_dots(const Rows& a, const Rows& b) {
  using Column = Eigen::Matrix<double, K, 1>;
  const Column sum = blocked_sum(int(a.size() / K), Column(Column::Zero()), [&](int i) {
    return Column(Eigen::Map<const Column>(&a[size_t(i) * K]).cwiseProduct(Eigen::Map<const Column>(&b[size_t(i) * K])));
  });
  std::array<double, K> out;
  for (int c = 0; c < K; ++c) out[size_t(c)] = sum[c];
  return out;
}

// out += sign * (row i of A Z).
template <int K>
inline void add_product_row(const AggregationLevel& l, int i, const double* Z, double sign, double* out) {
  for (int e = l.ptr[i]; e < l.ptr[i + 1]; ++e) {
    const double a = sign * l.val[e];
    const double* z = Z + size_t(l.idx[e]) * K;
    for (int c = 0; c < K; ++c) out[c] += a * z[c];
  }
}

// Row i of R - A Z.
template <int K>
inline void residual_row(const AggregationLevel& l, int i, const double* R, const double* Z, double* out) {
  for (int c = 0; c < K; ++c) out[c] = R[size_t(i) * K + c];
  add_product_row<K>(l, i, Z, -1.0, out);
}

// Scratch of one level for one solve: its smoothed iterate, and (below the finest) the restricted
// residual it is given and the correction it returns.
struct Scratch {
  Rows work, residual, correction;
};

template <int K>
void apply_cycle(const Parts& p, size_t level, const Rows& R, Rows& Z, std::vector<Scratch>& scratch);

// The correction of the level below `level` for the residual of `work` (restricted, cycled or
// solved there), added to `work`.
template <int K>
void coarse_correction(const Parts& p, size_t level, const Rows& R, std::vector<Scratch>& scratch) {
  const AggregationLevel& l = p.levels[level];
  Rows& work = scratch[level].work;
  const int nc = l.coarse_size;
  Rows& restricted = scratch[level + 1].residual;
#pragma omp parallel for schedule(dynamic, 1024)
  for (int a = 0; a < nc; ++a) {
    double sum[K] = {}, r[K];
    for (int m = l.member_offset[size_t(a)]; m < l.member_offset[size_t(a) + 1]; ++m) {
      residual_row<K>(l, l.member[size_t(m)], R.data(), work.data(), r);
      for (int c = 0; c < K; ++c) sum[c] += r[c];
    }
    for (int c = 0; c < K; ++c) restricted[size_t(a) * K + c] = sum[c];
  }
  Rows& correction = scratch[level + 1].correction;
  if (level + 1 < p.levels.size()) {
    apply_cycle<K>(p, level + 1, restricted, correction, scratch);
  } else {
    Eigen::Matrix<double, Eigen::Dynamic, K> b(nc, K);
    for (int a = 0; a < nc; ++a)
      for (int c = 0; c < K; ++c) b(a, c) = restricted[size_t(a) * K + c];
    const Eigen::Matrix<double, Eigen::Dynamic, K> solved = p.coarse.solve(b);
    for (int a = 0; a < nc; ++a)
      for (int c = 0; c < K; ++c) correction[size_t(a) * K + c] = solved(a, c);
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < l.n; ++i)
    for (int c = 0; c < K; ++c) work[size_t(i) * K + c] += correction[size_t(l.aggregate[size_t(i)]) * K + c];
}

// The symmetric V-cycle Z = cycle(R) from `level` down: damped Jacobi from zero, coarse correction
// (the residual's restriction fused with its computation), damped Jacobi again.
template <int K>
void apply_cycle(const Parts& p, size_t level, const Rows& R, Rows& Z, std::vector<Scratch>& scratch) {
  const AggregationLevel& l = p.levels[level];
  const std::vector<double>& w = l.damped_inverse_diagonal;
  Rows& work = scratch[level].work;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < l.n; ++i)
    for (int c = 0; c < K; ++c) work[size_t(i) * K + c] = w[size_t(i)] * R[size_t(i) * K + c];
  coarse_correction<K>(p, level, R, scratch);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < l.n; ++i) {
    double r[K];
    residual_row<K>(l, i, R.data(), work.data(), r);
    for (int c = 0; c < K; ++c) Z[size_t(i) * K + c] = work[size_t(i) * K + c] + w[size_t(i)] * r[c];
  }
}

// Q = A D.
template <int K>
void multiply(const AggregationLevel& l, const Rows& D, Rows& Q) {
#pragma omp parallel for schedule(static)
  for (int i = 0; i < l.n; ++i) {
    double* q = &Q[size_t(i) * K];
    for (int c = 0; c < K; ++c) q[c] = 0;
    add_product_row<K>(l, i, D.data(), 1.0, q);
  }
}

template <int K>
std::vector<Scratch> scratch_for(const Parts& p) {
  std::vector<Scratch> scratch(p.levels.size() + 1);
  for (size_t k = 0; k < p.levels.size(); ++k) {
    scratch[k].work.resize(size_t(p.levels[k].n) * K);
    scratch[k + 1].residual.resize(size_t(p.levels[k].coarse_size) * K);
    scratch[k + 1].correction.resize(size_t(p.levels[k].coarse_size) * K);
  }
  return scratch;
}

// The multilevel V-cycle as a preconditioner of block_cg.
// Its columns iterate together: on a system where one column's relative residual says little
// (the Stanford bunny's base normals, with unreferenced vertices), stopping that column early
// moved Relief Edges' curves by a fifth of their length.
template <int K>
struct CyclePreconditioner {
  static constexpr bool kStopEachColumn = false;
  const Parts& parts;
  std::vector<Scratch> scratch = scratch_for<K>(parts);
  void apply(const Rows& r, Rows& z) { apply_cycle<K>(parts, 0, r, z, scratch); }
};

// The inverse diagonal (Jacobi) as a preconditioner of block_cg; a row without a positive
// diagonal is left unscaled.
// Each column stops on its own, as Eigen's ConjugateGradient (which this replaced) did: iterating
// on a column whose right-hand side is rounding noise (the x and y of a flat heat step) makes the
// result depend on that noise (a translated mesh came out 6e-7 apart instead of 3e-15).
template <int K>
struct JacobiPreconditioner {
  static constexpr bool kStopEachColumn = true;
  const std::vector<double>& inverse_diagonal;
  void apply(const Rows& r, Rows& z) const {
#pragma omp parallel for schedule(static)
    for (int i = 0; i < int(inverse_diagonal.size()); ++i) {
      const double w = inverse_diagonal[size_t(i)] > 0 ? inverse_diagonal[size_t(i)] : 1.0;
      for (int c = 0; c < K; ++c) z[size_t(i) * K + c] = w * r[size_t(i) * K + c];
    }
  }
};

// Conjugate gradients on K columns of B at once, from the columns `first`.. of X, on the matrix of
// `fine`. (Fusing the vector updates with the dot products into fewer passes was tried: slower.)
template <int K, class Preconditioner>
int block_cg(const AggregationLevel& fine, Preconditioner& precondition, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
             int first, double tolerance, int max_iterations) {
  const int n = int(B.rows());
  Rows x(size_t(n) * K), r(size_t(n) * K), z(size_t(n) * K), d(size_t(n) * K), q(size_t(n) * K);
  std::array<double, K> b_norm{};
  for (int c = 0; c < K; ++c) b_norm[size_t(c)] = B.col(first + c).norm();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < K; ++c) x[size_t(i) * K + c] = X(i, first + c), z[size_t(i) * K + c] = B(i, first + c);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) residual_row<K>(fine, i, z.data(), x.data(), &r[size_t(i) * K]);
  precondition.apply(r, z);
  d = z;
  std::array<double, K> rz = column_dots<K>(r, z);
  // With Preconditioner::kStopEachColumn a column stops where its residual first reaches the
  // tolerance, as when solved alone; else every column iterates until all have reached it.
  std::array<bool, K> done{};
  auto converged = [&] {
    const std::array<double, K> rr = column_dots<K>(r, r);
    bool all = true;
    for (int c = 0; c < K; ++c) {
      const bool now = std::sqrt(rr[size_t(c)]) <= tolerance * (b_norm[size_t(c)] > 0 ? b_norm[size_t(c)] : 1.0);
      all = all && now;
      if (Preconditioner::kStopEachColumn) done[size_t(c)] = done[size_t(c)] || now;
    }
    return all;
  };
  int iteration = 0;
  while (iteration < max_iterations && !converged()) {
    ++iteration;
    multiply<K>(fine, d, q);
    const std::array<double, K> dq = column_dots<K>(d, q);
    std::array<double, K> alpha{}, beta{};
    for (int c = 0; c < K; ++c)
      alpha[size_t(c)] = !done[size_t(c)] && dq[size_t(c)] > 0 ? rz[size_t(c)] / dq[size_t(c)] : 0.0;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < K; ++c) {
        x[size_t(i) * K + c] += alpha[size_t(c)] * d[size_t(i) * K + c];
        r[size_t(i) * K + c] -= alpha[size_t(c)] * q[size_t(i) * K + c];
      }
    precondition.apply(r, z);
    const std::array<double, K> rz_next = column_dots<K>(r, z);
    for (int c = 0; c < K; ++c) beta[size_t(c)] = rz[size_t(c)] > 0 ? rz_next[size_t(c)] / rz[size_t(c)] : 0.0;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < K; ++c) d[size_t(i) * K + c] = z[size_t(i) * K + c] + beta[size_t(c)] * d[size_t(i) * K + c];
    rz = rz_next;
  }
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < K; ++c) X(i, first + c) = x[size_t(i) * K + c];
  return iteration;
}

template <int K>
int multilevel_block_cg(const Parts& p, const Eigen::MatrixXd& B, Eigen::MatrixXd& X, int first, double tolerance,
                        int max_iterations) {
  CyclePreconditioner<K> cycle{p};
  return block_cg<K>(p.levels.front(), cycle, B, X, first, tolerance, max_iterations);
}

template <int K>
int jacobi_block_cg(const AggregationLevel& l, const Eigen::MatrixXd& B, Eigen::MatrixXd& X, int first,
                    double tolerance, int max_iterations) {
  JacobiPreconditioner<K> jacobi{l.damped_inverse_diagonal};
  return block_cg<K>(l, jacobi, B, X, first, tolerance, max_iterations);
}

// Runs solve_block<K>(first, ...) on the columns of B three at a time (the x, y, z of positions
// and normals); returns the most iterations a block needed.
template <typename SolveBlock>
int in_blocks_of_three(const Eigen::MatrixXd& B, SolveBlock solve_block) {
  int iterations = 0;
  for (int first = 0; first < B.cols();) {
    const int k = std::min<int>(3, int(B.cols()) - first);
    const int its = k == 3 ? solve_block(std::integral_constant<int, 3>(), first)
                    : k == 2 ? solve_block(std::integral_constant<int, 2>(), first)
                             : solve_block(std::integral_constant<int, 1>(), first);
    iterations = std::max(iterations, its);
    first += k;
  }
  return iterations;
}

}  // namespace

int preconditioned_cg(const MultilevelPreconditioner& M, const Eigen::MatrixXd& B, Eigen::MatrixXd& X, double tolerance,
                      int max_iterations) {
  return in_blocks_of_three(B, [&](auto k, int first) {
    return multilevel_block_cg<decltype(k)::value>(M.parts(), B, X, first, tolerance, max_iterations);
  });
}

int jacobi_cg(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X, double tolerance,
              int max_iterations) {
  Eigen::SparseMatrix<double> compressed;
  if (!A.isCompressed()) compressed = A, compressed.makeCompressed();
  AggregationLevel level;
  level.view(A.isCompressed() ? A : compressed);
  inverse_diagonal(level, 1.0);
  return in_blocks_of_three(B, [&](auto k, int first) {
    return jacobi_block_cg<decltype(k)::value>(level, B, X, first, tolerance, max_iterations);
  });
}

}  // namespace reliefkit
