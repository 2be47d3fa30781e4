// ReliefKit — sparse symmetric positive-definite solves, shared by every core that needs one
// (base normals now; multi-scale diffusion and drawing reconstruction next).
//
// Solvers behind one call:
//  - iterative: conjugate gradients with a diagonal (Jacobi) preconditioner, started from the
//    caller's guess, three columns at a time with every loop on every core (jacobi_cg,
//    reliefkit/base/multilevel.h; it replaced Eigen's ConjugateGradient, which solves column after
//    column with its vector updates on one core: `python3 bench/compare_meshlab.py chapters`,
//    docs/benchmarks.md, has the multi-scale filters' times before and after);
//  - multilevel: the same preconditioned by an aggregation V-cycle, for stiff systems;
//  - direct: CHOLMOD's supernodal Cholesky factorization (SuiteSparse, through Eigen's
//    CholmodSupport; fill-reducing ordering chosen by CHOLMOD), exact up to rounding whatever the
//    conditioning, but its time and memory grow faster than the mesh (measured on the relief
//    torus: 3.1 s and 0.3 GB at 500 K unknowns, 17 s and 2.2 GB at 2 M; docs/relief_edges.md).
// `Auto` takes the iterative solver unless the caller says the system is ill-conditioned
// (`prefer_direct`) and it is small enough for the direct one, and falls back to the other solver
// when the first fails (no convergence within the iteration limit, factorization failure, out of
// memory). Every solve ends with the true relative residual max_k |A x_k - b_k| / |b_k| measured
// on the result, whichever solver produced it, so a caller can always say how good it is.
#pragma once

#include <complex>

#include <Eigen/Sparse>
#include <memory>
#include <string>

#include "reliefkit/base/mesh.h"

namespace reliefkit {

/// A symmetric matrix's compressed columns are its compressed rows: the row-major view of the same
/// arrays lets Eigen's sparse products run on every core.
inline Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor>> row_major(const Eigen::SparseMatrix<double>& A) {
  return {A.rows(), A.cols(), A.nonZeros(), A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr()};
}

/// Auto: Multilevel when the caller expects an ill-conditioned system (prefer_direct), else Iterative;
/// each falls back to Direct when it does not converge (and Direct to Iterative).
enum class SolverMethod { Auto, Iterative, Direct, Multilevel };

struct SolverOptions {
  SolverMethod method = SolverMethod::Auto;
  double tolerance = 1e-6;   // relative residual the iterative solver aims at (per column)
  int max_iterations = 1000; // conjugate-gradient limit per column
  bool prefer_direct = false;  // Auto: the caller expects many iterations (ill-conditioned system)
  Progress progress = nullptr;
  int progress_from = 0, progress_to = 100;  // the share of the caller's progress bar
  const char* label = "Solve";
};

struct SolveReport {
  std::string method;        // "conjugate gradients", "Cholesky (CHOLMOD)", or both when one fell back
  int iterations = 0;        // conjugate-gradient iterations (largest over the columns), 0 if direct only
  double residual = 0;       // max over the columns of |A x - b| / |b|, measured on the result
  bool converged = false;    // residual <= tolerance (a direct solve: <= max(tolerance, 1e-8))
  std::string note;          // why a fallback happened (empty when none)
  std::string summary() const;  // "conjugate gradients, 132 iterations, residual 9.7e-04"
};

/// Solves A X = B for a symmetric positive-definite A (both triangles stored). X holds the initial
/// guess on entry when its size matches B (the iterative solver starts from it), the solution on
/// return. Never throws for a numerical failure: the report says what happened; throws InputError
/// only for inconsistent sizes.
SolveReport solve_spd(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
                      const SolverOptions& options = {});

/// A Hermitian matrix stored by rows, both triangles.
using HermitianMatrix = Eigen::SparseMatrix<std::complex<double>, Eigen::RowMajor>;

/// Solves A x = b for a Hermitian positive-definite A: Jacobi-preconditioned conjugate gradients
/// in complex arithmetic (the iterates of the same method on the real form of twice the size, at
/// well under half its memory traffic: a 2 x 2 rotation block is one complex number) on every
/// core; when they do not converge, solve_spd on real_form(A) (its Cholesky fallback). x: initial
/// guess in (when its size matches), solution out; the report as solve_spd's.
SolveReport solve_hpd(const HermitianMatrix& A, const Eigen::VectorXcd& b, Eigen::VectorXcd& x,
                      const SolverOptions& options = {});

/// The real symmetric form of twice the size: entry a + ib becomes the block [[a, -b], [b, a]]
/// (rows and columns 2i, 2i+1 hold the real and imaginary parts of unknown i).
Eigen::SparseMatrix<double> real_form(const HermitianMatrix& A);

/// Conjugate-gradient iterations predicted for a "mass + stiffness" system A = M + K (diagonal
/// mass M): about sqrt(condition number), the condition number about the median of A_ii / M_i.
/// Measured (build/bench/bench_solvers, bench_curves): 467 iterations at a heat step of 52 edge
/// lengths on the noisy cylinder relief, 391 at 60 on the relief torus (1 M faces), 561 at 4 M.
double predicted_cg_iterations(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& mass);
/// The same from the median of A_ii / M_i, for a caller that knows it (a heat step M + dtau K:
/// 1 + dtau x the median of K_ii / M_i).
double predicted_cg_iterations(double median_diagonal_ratio);
/// A Cholesky factorization costs what conjugate gradients spend on about 400 iterations (3.1 s
/// at 1 M faces) to 340 (17 s at 4 M): above this prediction, callers set prefer_direct.
constexpr double kDirectAboveIterations = 400;
/// Above this prediction, conjugate gradients preconditioned by the multilevel cycle
/// (reliefkit/base/multilevel.h) cost less than Jacobi-preconditioned ones, set-up included, and
/// stay accurate where the prediction is far too low (irregular scans). Base normals at 15 edge
/// lengths, `build/bench/bench_solvers --repeat 2 fertility.ply penny.ply stanford-bunny.obj`:
/// Jacobi 633 / 125 / 148 iterations, 0.34 / 0.24 / 0.13 s (the bunny's normals up to 122 deg
/// from the exact ones at the residual asked), multilevel (two levels on these) 19 / 15 / 18, 0.05 / 0.13 / 0.11 s
/// (within 0.01 deg). Predicted for the statuette and the coin: 147 and 126.
constexpr double kMultilevelAboveIterations = 60;

/// Largest system Auto hands to the direct solver (unknowns); larger ones stay iterative.
constexpr int kDirectMaxUnknowns = 2500000;

/// Before CHOLMOD first factorizes: where the BLAS it calls is OpenBLAS (Debian's default), it is
/// set to one thread for the process. OpenBLAS's own threads wait for work spinning on
/// sched_yield and take the cores from the OpenMP loops around the solves:
/// `time build/tests/reliefkit_unit_tests --gtest_filter=BaseLibrary.DeformationFitsTheOutline`
/// 7.3 s (13.6 s of CPU) with them, 5.2 s (7.4 s) with OPENBLAS_NUM_THREADS=1; Relief Edges on a
/// 1 M-face relief no slower (its log line, `scripts/meshlabserver -i relief1000000.ply -s` the
/// Relief Edges filter of examples/relief_edges.mlx twice, with and without that variable:
/// 2.0-2.6 s against 1.9-2.1 s).
void use_one_blas_thread();

/// A Cholesky factorization (CHOLMOD) kept across the solves of systems that share one sparsity
/// pattern: the fill-reducing ordering is computed for the first matrix and the numeric
/// factorization again only when the values change, so a repeated matrix costs its solve alone.
class SpdFactorization {
 public:
  /// Amd: AMD alone, quick to compute (best for one factorization). Best: CHOLMOD's own choice
  /// (METIS too when AMD's fill is high): slower to compute, less fill for many factorizations.
  enum class Ordering { Amd, Best };
  explicit SpdFactorization(Ordering ordering = Ordering::Amd);
  ~SpdFactorization();
  SpdFactorization(const SpdFactorization&) = delete;
  SpdFactorization& operator=(const SpdFactorization&) = delete;

  /// Factorizes A (symmetric, both triangles stored) unless it is the matrix factorized last.
  /// False, with the reason in `why`, when the ordering or the factorization fails.
  bool factorize(const Eigen::SparseMatrix<double>& A, std::string& why);
  /// X = A^-1 B for the matrix factorized last; false when the solve fails or is not finite.
  bool solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X);
  int orderings() const;       // sparsity patterns ordered so far
  int factorizations() const;  // numeric factorizations so far

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// solve_spd by Cholesky alone, with the factorization kept in `factorization` for the next call
/// (options.method is not read). Never throws for a numerical failure: the report says what
/// happened (converged false, note); throws InputError only for inconsistent sizes.
SolveReport solve_spd(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
                      SpdFactorization& factorization, const SolverOptions& options = {});

}  // namespace reliefkit
