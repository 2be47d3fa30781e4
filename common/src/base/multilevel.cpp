#include "reliefkit/base/multilevel.h"

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

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

struct TwoLevelPreconditioner::Parts {
  Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor>> A;
  std::vector<double> damped_inverse_diagonal;  // ω / A_ii
  std::vector<int> aggregate;                   // the prolongation: a coarse value is copied to its aggregate
  std::vector<int> member_offset, member;       // the rows of each aggregate (the restriction's sums)
  int coarse_size = 0;
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> coarse;
  bool ok = false;
  explicit Parts(const Eigen::SparseMatrix<double>& a) : A(row_major(a)) { use_one_blas_thread(); }
};

namespace {

using Parts = TwoLevelPreconditioner::Parts;

// The rows of each aggregate, as offsets into one list.
void list_members(Parts& p) {
  const int n = int(p.aggregate.size());
  p.member_offset.assign(size_t(p.coarse_size) + 1, 0);
  for (int a : p.aggregate) ++p.member_offset[size_t(a) + 1];
  for (int c = 0; c < p.coarse_size; ++c) p.member_offset[size_t(c) + 1] += p.member_offset[size_t(c)];
  p.member.resize(size_t(n));
  std::vector<int> next(p.member_offset.begin(), p.member_offset.end() - 1);
  for (int i = 0; i < n; ++i) p.member[size_t(next[size_t(p.aggregate[size_t(i)])]++)] = i;
}

// Sorts the entries of one column (from `first` to the end) by row.
void sort_column(std::vector<int>& inner, std::vector<double>& value, size_t first) {
  std::vector<std::pair<int, double>> column;
  for (size_t k = first; k < inner.size(); ++k) column.emplace_back(inner[k], value[k]);
  std::sort(column.begin(), column.end());
  for (size_t k = first; k < inner.size(); ++k) inner[k] = column[k - first].first, value[k] = column[k - first].second;
}

// Galerkin coarse operator Pᵀ A P, lower triangle: the couplings summed aggregate by aggregate,
// assembled column by column (no triplet sort).
Eigen::SparseMatrix<double> coarse_operator(const Parts& p) {
  const int nc = p.coarse_size;
  const int* ptr = p.A.outerIndexPtr();
  const int* idx = p.A.innerIndexPtr();
  const double* val = p.A.valuePtr();
  std::vector<int> slot(size_t(nc), -1), outer(size_t(nc) + 1, 0), inner;
  std::vector<double> value;
  inner.reserve(size_t(p.A.nonZeros()) / 4);
  value.reserve(size_t(p.A.nonZeros()) / 4);
  for (int c = 0; c < nc; ++c) {
    const size_t first = inner.size();
    for (int m = p.member_offset[size_t(c)]; m < p.member_offset[size_t(c) + 1]; ++m)
      for (int e = ptr[p.member[size_t(m)]]; e < ptr[p.member[size_t(m)] + 1]; ++e) {
        const int r = p.aggregate[size_t(idx[e])];
        if (r < c) continue;
        if (slot[size_t(r)] < int(first)) slot[size_t(r)] = int(inner.size()), inner.push_back(r), value.push_back(0);
        value[size_t(slot[size_t(r)])] += val[e];
      }
    outer[size_t(c) + 1] = int(inner.size());
    sort_column(inner, value, first);  // CHOLMOD wants each column's rows in order
  }
  Eigen::SparseMatrix<double> coarse(nc, nc);
  coarse.resizeNonZeros(Eigen::Index(inner.size()));
  std::copy(outer.begin(), outer.end(), coarse.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), coarse.innerIndexPtr());
  std::copy(value.begin(), value.end(), coarse.valuePtr());
  return coarse;
}

}  // namespace

TwoLevelPreconditioner::TwoLevelPreconditioner(const Eigen::SparseMatrix<double>& A) : parts_(new Parts(A)) {
  const int n = int(A.rows());
  Parts& p = *parts_;
  p.damped_inverse_diagonal.resize(size_t(n));
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const int* cols = p.A.innerIndexPtr() + p.A.outerIndexPtr()[i];
    const int len = p.A.outerIndexPtr()[i + 1] - p.A.outerIndexPtr()[i];
    const int* at = std::lower_bound(cols, cols + len, i);
    const double d = (at != cols + len && *at == i) ? p.A.valuePtr()[p.A.outerIndexPtr()[i] + (at - cols)] : 0.0;
    p.damped_inverse_diagonal[size_t(i)] = d > 0 ? kJacobiDamping / d : 0;
  }
  p.aggregate = aggregate_vertices(A, p.coarse_size);
  list_members(p);
  p.coarse.cholmod().print = 0;
  // Simplicial: the coarse system is small and sparse, where the supernodal method's dense
  // blocks cost more than they save (a trial at 60 K unknowns while writing this: about 0.4 s
  // against 0.7 s on a loaded machine).
  p.coarse.cholmod().supernodal = CHOLMOD_SIMPLICIAL;
  p.coarse.cholmod().nmethods = 1;
  p.coarse.cholmod().method[0].ordering = CHOLMOD_AMD;
  p.coarse.compute(coarse_operator(p));
  p.ok = p.coarse.info() == Eigen::Success;
}

TwoLevelPreconditioner::~TwoLevelPreconditioner() = default;
bool TwoLevelPreconditioner::ok() const { return parts_->ok; }
int TwoLevelPreconditioner::coarse_size() const { return parts_->coarse_size; }

namespace {

// Blocks of K columns stored row by row (the K values of a row side by side): the sparse products
// then read each neighbour's values from one cache line. Buffers are allocated once per solve.
using Rows = std::vector<double>;

constexpr int kReductionBlock = 4096;  // rows per partial sum: the same sums on any number of cores

// Per column, Σ_i a_i b_i, summed in fixed blocks (reproducible whatever the number of threads).
template <int K>
std::array<double, K> column_dots(const Rows& a, const Rows& b) {
  const int n = int(a.size() / K), blocks = (n + kReductionBlock - 1) / kReductionBlock;
  std::vector<std::array<double, K>> partial(static_cast<size_t>(blocks));
#pragma omp parallel for schedule(static)
  for (int blk = 0; blk < blocks; ++blk) {
    std::array<double, K> s{};
    for (int i = blk * kReductionBlock; i < std::min(n, (blk + 1) * kReductionBlock); ++i)
      for (int c = 0; c < K; ++c) s[size_t(c)] += a[size_t(i) * K + c] * b[size_t(i) * K + c];
    partial[size_t(blk)] = s;
  }
  std::array<double, K> sum{};
  for (const auto& s : partial)
    for (int c = 0; c < K; ++c) sum[size_t(c)] += s[size_t(c)];
  return sum;
}

// out += sign * (row i of A Z).
template <int K>
inline void add_product_row(const Parts& p, int i, const double* Z, double sign, double* out) {
  const int* ptr = p.A.outerIndexPtr();
  const int* idx = p.A.innerIndexPtr();
  const double* val = p.A.valuePtr();
  for (int e = ptr[i]; e < ptr[i + 1]; ++e) {
    const double a = sign * val[e];
    const double* z = Z + size_t(idx[e]) * K;
    for (int c = 0; c < K; ++c) out[c] += a * z[c];
  }
}

// Row i of R - A Z.
template <int K>
inline void residual_row(const Parts& p, int i, const double* R, const double* Z, double* out) {
  for (int c = 0; c < K; ++c) out[c] = R[size_t(i) * K + c];
  add_product_row<K>(p, i, Z, -1.0, out);
}

// The symmetric two-grid cycle Z = cycle(R): damped Jacobi from zero, coarse correction (the
// residual's restriction fused with its computation), damped Jacobi again. `work`: n x K scratch.
template <int K>
void apply_cycle(const Parts& p, const Rows& R, Rows& Z, Rows& work) {
  const int n = int(p.aggregate.size()), nc = p.coarse_size;
  const std::vector<double>& w = p.damped_inverse_diagonal;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < K; ++c) work[size_t(i) * K + c] = w[size_t(i)] * R[size_t(i) * K + c];
  Eigen::MatrixXd coarse_residual(nc, K);
#pragma omp parallel for schedule(dynamic, 1024)
  for (int a = 0; a < nc; ++a) {
    double sum[K] = {}, r[K];
    for (int m = p.member_offset[size_t(a)]; m < p.member_offset[size_t(a) + 1]; ++m) {
      residual_row<K>(p, p.member[size_t(m)], R.data(), work.data(), r);
      for (int c = 0; c < K; ++c) sum[c] += r[c];
    }
    for (int c = 0; c < K; ++c) coarse_residual(a, c) = sum[c];
  }
  const Eigen::MatrixXd correction = p.coarse.solve(coarse_residual);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < K; ++c) work[size_t(i) * K + c] += correction(p.aggregate[size_t(i)], c);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double r[K];
    residual_row<K>(p, i, R.data(), work.data(), r);
    for (int c = 0; c < K; ++c) Z[size_t(i) * K + c] = work[size_t(i) * K + c] + w[size_t(i)] * r[c];
  }
}

// Q = A D.
template <int K>
void multiply(const Parts& p, const Rows& D, Rows& Q) {
  const int n = int(p.aggregate.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double* q = &Q[size_t(i) * K];
    for (int c = 0; c < K; ++c) q[c] = 0;
    add_product_row<K>(p, i, D.data(), 1.0, q);
  }
}

// Conjugate gradients on K columns of B at once, from the columns `first`.. of X.
template <int K>
int block_cg(const Parts& p, const Eigen::MatrixXd& B, Eigen::MatrixXd& X, int first, double tolerance,
             int max_iterations) {
  const int n = int(B.rows());
  Rows x(size_t(n) * K), r(size_t(n) * K), z(size_t(n) * K), d(size_t(n) * K), q(size_t(n) * K),
      work(size_t(n) * K);
  std::array<double, K> b_norm{};
  for (int c = 0; c < K; ++c) b_norm[size_t(c)] = B.col(first + c).norm();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < K; ++c) x[size_t(i) * K + c] = X(i, first + c), z[size_t(i) * K + c] = B(i, first + c);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) residual_row<K>(p, i, z.data(), x.data(), &r[size_t(i) * K]);
  apply_cycle<K>(p, r, z, work);
  d = z;
  std::array<double, K> rz = column_dots<K>(r, z);
  auto converged = [&] {
    const std::array<double, K> rr = column_dots<K>(r, r);
    for (int c = 0; c < K; ++c)
      if (std::sqrt(rr[size_t(c)]) > tolerance * (b_norm[size_t(c)] > 0 ? b_norm[size_t(c)] : 1.0)) return false;
    return true;
  };
  int iteration = 0;
  while (iteration < max_iterations && !converged()) {
    ++iteration;
    multiply<K>(p, d, q);
    const std::array<double, K> dq = column_dots<K>(d, q);
    std::array<double, K> alpha{}, beta{};
    for (int c = 0; c < K; ++c) alpha[size_t(c)] = dq[size_t(c)] > 0 ? rz[size_t(c)] / dq[size_t(c)] : 0.0;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < K; ++c) {
        x[size_t(i) * K + c] += alpha[size_t(c)] * d[size_t(i) * K + c];
        r[size_t(i) * K + c] -= alpha[size_t(c)] * q[size_t(i) * K + c];
      }
    apply_cycle<K>(p, r, z, work);
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

}  // namespace

int preconditioned_cg(const TwoLevelPreconditioner& M, const Eigen::MatrixXd& B, Eigen::MatrixXd& X, double tolerance,
                      int max_iterations) {
  const Parts& p = M.parts();
  int iterations = 0;
  for (int first = 0; first < B.cols();) {  // three columns at a time (the base normals' x, y, z)
    const int k = std::min<int>(3, int(B.cols()) - first);
    const int its = k == 3   ? block_cg<3>(p, B, X, first, tolerance, max_iterations)
                    : k == 2 ? block_cg<2>(p, B, X, first, tolerance, max_iterations)
                             : block_cg<1>(p, B, X, first, tolerance, max_iterations);
    iterations = std::max(iterations, its);
    first += k;
  }
  return iterations;
}

}  // namespace reliefkit
