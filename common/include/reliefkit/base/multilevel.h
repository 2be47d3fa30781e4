// ReliefKit — conjugate gradients with a multilevel (aggregation) preconditioner, for the stiff
// "mass + t stiffness" systems of wide heat steps (base normals at 15-250 edge lengths).
//
// Jacobi-preconditioned conjugate gradients need about sqrt(condition) iterations, and the
// condition of M + t K grows with t / h²: at a base scale of 60 edges on a 1 M-face mesh that is
// 400 iterations, and CHOLMOD's factorization of the whole system costs as much. What those
// iterations spend their time on is the smooth part of the error, which a coarse copy of the system
// represents with a fraction of the unknowns. So the preconditioner is a V-cycle of
// aggregation-based algebraic multigrid (Vaněk, Mandel, Brezina 1996; Notay 2010), built from the
// matrix alone:
//   - aggregates: greedy, each a vertex with its still-free neighbours (the matrix graph is the
//     mesh's edge graph), left-over vertices joining the neighbouring aggregate they are most
//     strongly coupled to — about 1/8 of the unknowns;
//   - prolongation P: the aggregates' indicators (piecewise constant); smoothing P by a Jacobi
//     step, as smoothed aggregation does, saved 3 of 17 iterations at 60 edges but made the set-up
//     about 3x dearer (tried, not kept);
//   - coarse operator Pᵀ A P (Galerkin: the couplings summed aggregate by aggregate), aggregated
//     again while it has more than kLargestFactorizedLevel unknowns; the last one factorized once
//     by CHOLMOD. A 1 M-face mesh has three levels (500 K, 60 K and 7 K unknowns); against two
//     levels (the 60 K one factorized), `build/bench/bench_solvers --sizes 1000000`: set-up 0.055 s
//     instead of 0.29-0.32 s, 15 / 21 / 23 iterations instead of 11 / 16 / 17 at 15 / 60 / 227 edge
//     lengths, 0.35 / 0.49 / 0.53 s instead of 0.68 / 0.80 / 0.89 s in all. Meshes below about
//     300 K faces keep two levels;
//   - cycle: damped Jacobi, coarse correction (recursively), damped Jacobi — symmetric, so it is a
//     valid preconditioner for conjugate gradients.
// On the 1 M-face relief torus with two levels: 11, 17 and 21 iterations at 15, 60 and 227 edge
// lengths, where Jacobi-preconditioned conjugate gradients take 131, 391 and over 1,000.
// Measured figures (iterations, time, angle to the exact solve): bench/bench_solvers, docs/benchmarks.md.
#pragma once

#include <Eigen/Sparse>
#include <memory>

namespace reliefkit {

/// Levels coarser than this many unknowns are factorized, larger ones aggregated again.
constexpr int kLargestFactorizedLevel = 20000;

/// The V-cycle for one SPD matrix (both triangles stored); `largest_factorized` as above (tests
/// pass less to reach more levels on a small mesh). Building it fails (ok() false) when the coarse
/// factorization does; preconditioned_cg() then must not be given it.
class MultilevelPreconditioner {
 public:
  explicit MultilevelPreconditioner(const Eigen::SparseMatrix<double>& A,
                                   int largest_factorized = kLargestFactorizedLevel);
  ~MultilevelPreconditioner();
  bool ok() const;
  int coarse_size() const;  // unknowns of the factorized level
  int levels() const;       // counting the finest and the factorized one
  struct Parts;  // the levels (matrix, smoother, aggregates) and the coarse factorization (multilevel.cpp)
  const Parts& parts() const { return *parts_; }

 private:
  std::unique_ptr<Parts> parts_;
};

/// Aggregates of the matrix graph: aggregate[i] for every row, numbered 0..count-1.
std::vector<int> aggregate_vertices(const Eigen::SparseMatrix<double>& A, int& count);

/// Preconditioned conjugate gradients on the columns of B, three at a time (X: initial guess in,
/// solution out), until each column's relative residual is at most `tolerance` or
/// `max_iterations`; the system's matrix is the preconditioner's. Returns the most iterations a
/// block needed.
int preconditioned_cg(const MultilevelPreconditioner& preconditioner, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
                      double tolerance, int max_iterations);

/// The same with the Jacobi preconditioner (A's inverse diagonal) for the well-conditioned systems
/// (short heat steps): every loop on every core and the matrix read once per iteration for three
/// columns, where Eigen's ConjugateGradient solves column after column with its vector updates on
/// one core. A: SPD, both triangles stored.
int jacobi_cg(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, Eigen::MatrixXd& X, double tolerance,
              int max_iterations);

}  // namespace reliefkit
