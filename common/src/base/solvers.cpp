#include "reliefkit/base/solvers.h"

#include <dlfcn.h>

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <vector>

#include "reliefkit/base/multilevel.h"
#include "reliefkit/base/reductions.h"

namespace reliefkit {

std::string SolveReport::summary() const {
  char buf[160];
  if (iterations > 0)
    std::snprintf(buf, sizeof buf, "%s, %d iterations, residual %.1e", method.c_str(), iterations, residual);
  else
    std::snprintf(buf, sizeof buf, "%s, residual %.1e", method.c_str(), residual);
  return buf;
}

namespace {

double relative_residual(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& X) {
  if (!X.allFinite()) return std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd R = row_major(A) * X - B;
  double worst = 0;
  for (int k = 0; k < B.cols(); ++k) {
    const double b = B.col(k).norm(), r = R.col(k).norm();
    worst = std::max(worst, b > 0 ? r / b : r);
  }
  return worst;
}

void report_progress(const SolverOptions& o, double share, const char* what) {
  if (o.progress) o.progress(o.progress_from + int(share * (o.progress_to - o.progress_from)), what);
}

// Jacobi-preconditioned conjugate gradients, three columns at a time (reliefkit/base/multilevel.h).
bool iterative(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
               const SolverOptions& o, SolveReport& rep) {
  report_progress(o, 0.0, o.label);
  const int iterations = jacobi_cg(A, B, X, o.tolerance, std::max(1, o.max_iterations));
  rep.iterations = std::max(rep.iterations, iterations);
  rep.residual = relative_residual(A, B, X);
  return rep.residual <= o.tolerance;
}

// CHOLMOD's supernodal Cholesky factorization, kept in `f`. Out of memory and a matrix that is not
// numerically positive definite both end in a report, not an exception.
bool direct(SpdFactorization& f, const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
            const SolverOptions& o, SolveReport& rep, std::string& why) {
  try {
    report_progress(o, 0.1, o.label);
    if (!f.factorize(A, why)) return false;
    report_progress(o, 0.9, o.label);
    Eigen::MatrixXd Y;
    if (!f.solve(B, Y)) {
      why = "the Cholesky solve failed";
      return false;
    }
    const double res = relative_residual(A, B, Y);
    if (!(res <= std::max(o.tolerance, 1e-8))) {
      char buf[120];
      std::snprintf(buf, sizeof buf, "the Cholesky solution has a residual of %.1e", res);
      why = buf;
      return false;
    }
    X = std::move(Y);
    rep.residual = res;
    return true;
  } catch (const std::bad_alloc&) {
    why = "not enough memory for the Cholesky factorization";
    return false;
  }
}
// The same with a factorization of its own (AMD ordering: see SpdFactorization).
bool direct(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
            const SolverOptions& o, SolveReport& rep, std::string& why) {
  SpdFactorization f;
  return direct(f, A, B, X, o, rep, why);
}

bool same_pattern(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a.nonZeros() == b.nonZeros() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

// Conjugate gradients preconditioned by the multilevel cycle (reliefkit/base/multilevel.h).
bool multilevel(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
               const SolverOptions& o, SolveReport& rep, std::string& why) {
  try {
    report_progress(o, 0.05, o.label);
    const MultilevelPreconditioner cycle(A);
    if (!cycle.ok()) {
      why = "the coarse system of the multilevel preconditioner could not be factorized";
      return false;
    }
    report_progress(o, 0.2, o.label);
    rep.iterations = preconditioned_cg(cycle, B, X, o.tolerance, std::max(1, o.max_iterations));
    rep.residual = relative_residual(A, B, X);
    if (rep.residual <= o.tolerance) return true;
    char buf[160];
    std::snprintf(buf, sizeof buf, "multilevel conjugate gradients stopped at %d iterations with a residual of %.1e",
                  rep.iterations, rep.residual);
    why = buf;
    return false;
  } catch (const std::bad_alloc&) {
    why = "not enough memory for the multilevel preconditioner";
    return false;
  }
}

}  // namespace

Eigen::SparseMatrix<double> real_form(const HermitianMatrix& A) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(size_t(A.nonZeros()) * 4);
  for (int i = 0; i < A.outerSize(); ++i)
    for (HermitianMatrix::InnerIterator it(A, i); it; ++it) {
      const int r = 2 * int(it.row()), c = 2 * int(it.col());
      const double a = it.value().real(), b = it.value().imag();
      entries.emplace_back(r, c, a), entries.emplace_back(r, c + 1, -b);
      entries.emplace_back(r + 1, c, b), entries.emplace_back(r + 1, c + 1, a);
    }
  Eigen::SparseMatrix<double> R(2 * A.rows(), 2 * A.cols());
  R.setFromTriplets(entries.begin(), entries.end());
  return R;
}

namespace {

// Jacobi-preconditioned conjugate gradients on a Hermitian positive-definite A, every loop on
// every core (Eigen's own keeps its vector updates on one). Returns the iterations; x in and out.
int hermitian_cg(const HermitianMatrix& A, const Eigen::VectorXcd& b, Eigen::VectorXcd& x, double tolerance,
                 int max_iterations) {
  using C = std::complex<double>;
  const int n = int(b.size());
  Eigen::VectorXd inverse_diagonal(n);
  Eigen::VectorXcd r(n), z(n), d(n), q(n);
  auto row_times = [&](const Eigen::VectorXcd& v, int i) {
    C sum = 0;
    for (HermitianMatrix::InnerIterator it(A, i); it; ++it) sum += it.value() * v[it.col()];
    return sum;
  };
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double a = A.coeff(i, i).real();
    inverse_diagonal[i] = a > 0 ? 1 / a : 1.0;
    r[i] = b[i] - row_times(x, i);
    z[i] = inverse_diagonal[i] * r[i];
    d[i] = z[i];
  }
  const double limit = tolerance * tolerance * std::max(blocked_sum(n, 0.0, [&](int i) { return std::norm(b[i]); }), 1e-300);
  const auto squared_and_preconditioned = [&](int i) {
    return Eigen::Vector2d(std::norm(r[i]), std::real(std::conj(r[i]) * z[i]));
  };
  const Eigen::Vector2d first = blocked_sum(n, Eigen::Vector2d(0, 0), squared_and_preconditioned);
  double rr = first[0], rz = first[1];
  int iteration = 0;
  for (; iteration < max_iterations && rr > limit; ++iteration) {
    const double dq = blocked_sum(n, 0.0, [&](int i) {
      q[i] = row_times(d, i);
      return std::real(std::conj(d[i]) * q[i]);
    });
    if (!(dq > 0)) break;
    const double alpha = rz / dq;
    // One pass: x and r updated, z = D⁻¹ r, and both |r|² and r·z for the next step.
    const Eigen::Vector2d sums = blocked_sum(n, Eigen::Vector2d(0, 0), [&](int i) {
      x[i] += alpha * d[i];
      r[i] -= alpha * q[i];
      z[i] = inverse_diagonal[i] * r[i];
      return squared_and_preconditioned(i);
    });
    rr = sums[0];
    const double rz_next = sums[1];
    const double beta = rz_next / rz;
    rz = rz_next;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) d[i] = z[i] + beta * d[i];
  }
  return iteration;
}

}  // namespace

SolveReport solve_hpd(const HermitianMatrix& A, const Eigen::VectorXcd& b, Eigen::VectorXcd& x,
                      const SolverOptions& o) {
  if (A.rows() != A.cols() || A.rows() != b.size())
    throw InputError("solve_hpd: the matrix must be square and match the right-hand side");
  if (x.size() != b.size() || !x.allFinite()) x = Eigen::VectorXcd::Zero(b.size());
  SolveReport rep;
  rep.method = "conjugate gradients";
  report_progress(o, 0, o.label);
  const Eigen::VectorXcd guess = x;
  rep.iterations = hermitian_cg(A, b, x, o.tolerance, std::max(1, o.max_iterations));
  const double bn = b.norm();
  rep.residual = (A * x - b).norm() / (bn > 0 ? bn : 1.0);
  rep.converged = rep.residual <= o.tolerance;
  report_progress(o, 1, o.label);
  if (rep.converged) return rep;
  // The real form through CHOLMOD (what solve_spd does after conjugate gradients stop).
  const int n = int(b.size());
  Eigen::MatrixXd B(2 * n, 1), X(2 * n, 1);
  for (int i = 0; i < n; ++i) B(2 * i, 0) = b[i].real(), B(2 * i + 1, 0) = b[i].imag();
  for (int i = 0; i < n; ++i) X(2 * i, 0) = guess[i].real(), X(2 * i + 1, 0) = guess[i].imag();
  SolverOptions direct = o;
  direct.method = SolverMethod::Direct;
  SolveReport real = solve_spd(real_form(A), B, X, direct);
  char buf[160];
  std::snprintf(buf, sizeof buf, "complex conjugate gradients stopped at %d iterations with a residual of %.1e",
                rep.iterations, rep.residual);
  real.note = real.note.empty() ? std::string(buf) : std::string(buf) + "; " + real.note;
  if (!(real.residual < rep.residual)) return rep;  // keep the better of the two
  for (int i = 0; i < n; ++i) x[i] = {X(2 * i, 0), X(2 * i + 1, 0)};
  return real;
}

double predicted_cg_iterations(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& mass) {
  std::vector<double> ratio;
  ratio.reserve(size_t(A.rows()));
  for (int i = 0; i < A.rows() && i < mass.size(); ++i)
    if (mass[i] > 0) ratio.push_back(A.coeff(i, i) / mass[i]);
  if (ratio.empty()) return 0;
  auto mid = ratio.begin() + ratio.size() / 2;
  std::nth_element(ratio.begin(), mid, ratio.end());
  return predicted_cg_iterations(*mid);
}

double predicted_cg_iterations(double median_diagonal_ratio) {
  constexpr double kIterationsPerRootCondition = 5.5;
  return kIterationsPerRootCondition * std::sqrt(std::max(1.0, median_diagonal_ratio));
}

SolveReport solve_spd(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
                      const SolverOptions& o) {
  if (A.rows() != A.cols() || A.rows() != B.rows())
    throw InputError("solve_spd: the matrix must be square and match the right-hand side");
  if (X.rows() != B.rows() || X.cols() != B.cols()) X = Eigen::MatrixXd::Zero(B.rows(), B.cols());
  for (int k = 0; k < X.cols(); ++k)
    if (!X.col(k).allFinite()) X.col(k).setZero();
  SolveReport rep;
  const Eigen::MatrixXd guess = X;
  const bool small_enough = A.rows() <= kDirectMaxUnknowns;
  const bool direct_first = o.method == SolverMethod::Direct ||
                            (o.method == SolverMethod::Auto && o.prefer_direct && small_enough);
  std::string why;
  // One attempt with one solver: true when it converged (the report then says which one).
  auto attempt = [&](const char* method, bool converged) {
    rep.method = method;
    if (converged) {
      rep.converged = true;
      report_progress(o, 1.0, o.label);
    } else {
      rep.note = rep.note.empty() ? why : rep.note + "; " + why;
    }
    return converged;
  };
  const bool multilevel_first = o.method == SolverMethod::Multilevel || (o.method == SolverMethod::Auto && o.prefer_direct);
  if (multilevel_first) {
    if (attempt("conjugate gradients, multilevel preconditioner", multilevel(A, B, X, o, rep, why))) return rep;
    X = guess;
  }
  if (direct_first) {
    if (attempt("Cholesky (CHOLMOD)", direct(A, B, X, o, rep, why))) return rep;
    if (o.method == SolverMethod::Direct) {
      rep.residual = relative_residual(A, B, X);
      return rep;
    }
    X = guess;
    rep.method = "conjugate gradients (after Cholesky failed)";
    rep.converged = iterative(A, B, X, o, rep);
    report_progress(o, 1.0, o.label);
    return rep;
  }
  rep.method = "conjugate gradients";
  rep.converged = iterative(A, B, X, o, rep);
  if (!rep.converged && o.method == SolverMethod::Auto && small_enough) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "conjugate gradients stopped at %d iterations with a residual of %.1e",
                  rep.iterations, rep.residual);
    const Eigen::MatrixXd cg = X;
    const double cg_residual = rep.residual;
    if (direct(A, B, X, o, rep, why)) {
      rep.method = "Cholesky (CHOLMOD, after conjugate gradients)";
      rep.note = buf;
      rep.converged = true;
    } else {
      X = cg;  // keep the better of the two
      rep.residual = cg_residual;
      rep.note = std::string(buf) + "; " + why;
    }
  }
  report_progress(o, 1.0, o.label);
  return rep;
}

void use_one_blas_thread() {
  static const bool done = [] {
    // The BLAS is found among the libraries already loaded, whatever scope its loader gave them
    // (MeshLab loads plugins with their own).
    for (const char* name : {"libblas.so.3", "libopenblas.so.0"}) {
      void* lib = dlopen(name, RTLD_LAZY | RTLD_NOLOAD);
      if (!lib) continue;
      using SetThreads = void (*)(int);
      if (auto set = reinterpret_cast<SetThreads>(dlsym(lib, "openblas_set_num_threads"))) set(1);
      dlclose(lib);
    }
    return true;
  }();
  (void)done;
}

struct SpdFactorization::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  Eigen::SparseMatrix<double> factored;  // the matrix of the current factorization (compressed)
  bool ordered = false, factored_ok = false;
  int orderings = 0, factorizations = 0;
};

SpdFactorization::SpdFactorization(Ordering ordering) : impl_(std::make_unique<Impl>()) {
  use_one_blas_thread();
  impl_->llt.cholmod().print = 0;  // CHOLMOD writes nothing to stdout; failures come back as info()
  // AMD alone: CHOLMOD's default also tries METIS when AMD's fill is high, and on a 4 M-face mesh
  // its nested dissection took 15 s to save little fill (33 s in all against 17 s with AMD).
  if (ordering == Ordering::Amd) {
    impl_->llt.cholmod().nmethods = 1;
    impl_->llt.cholmod().method[0].ordering = CHOLMOD_AMD;
  }
}
SpdFactorization::~SpdFactorization() = default;
int SpdFactorization::orderings() const { return impl_->orderings; }
int SpdFactorization::factorizations() const { return impl_->factorizations; }

bool SpdFactorization::factorize(const Eigen::SparseMatrix<double>& A_in, std::string& why) {
  Eigen::SparseMatrix<double> A = A_in;
  A.makeCompressed();
  Impl& m = *impl_;
  const bool pattern_kept = m.ordered && same_pattern(A, m.factored);
  if (pattern_kept && m.factored_ok && std::equal(A.valuePtr(), A.valuePtr() + A.nonZeros(), m.factored.valuePtr()))
    return true;
  if (!pattern_kept) {
    m.llt.analyzePattern(A);
    ++m.orderings;
    m.ordered = m.llt.info() == Eigen::Success;
    if (!m.ordered) {
      m.factored_ok = false;
      why = "the Cholesky ordering failed (not enough memory)";
      return false;
    }
  }
  m.llt.factorize(A);
  ++m.factorizations;
  m.factored = std::move(A);
  m.factored_ok = m.llt.info() == Eigen::Success;
  if (!m.factored_ok) why = "the Cholesky factorization failed (matrix not positive definite, or not enough memory)";
  return m.factored_ok;
}

bool SpdFactorization::solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) {
  if (!impl_->factored_ok) return false;
  X = impl_->llt.solve(B);
  return impl_->llt.info() == Eigen::Success && X.allFinite();
}

SolveReport solve_spd(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
                      SpdFactorization& factorization, const SolverOptions& o) {
  if (A.rows() != A.cols() || A.rows() != B.rows())
    throw InputError("solve_spd: the matrix must be square and match the right-hand side");
  SolveReport rep;
  rep.method = "Cholesky (CHOLMOD)";
  std::string why;
  rep.converged = direct(factorization, A, B, X, o, rep, why);
  if (!rep.converged) {
    rep.note = why;
    rep.residual = X.rows() == B.rows() && X.cols() == B.cols() ? relative_residual(A, B, X)
                                                                : std::numeric_limits<double>::infinity();
  }
  report_progress(o, 1.0, o.label);
  return rep;
}

}  // namespace reliefkit
