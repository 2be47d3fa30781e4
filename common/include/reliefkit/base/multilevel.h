// ReliefKit — conjugate gradients with a two-level (aggregation) preconditioner, for the stiff
// "mass + t stiffness" systems of wide heat steps (base normals at 50-250 edge lengths).
//
// Jacobi-preconditioned conjugate gradients need about sqrt(condition) iterations, and the
// condition of M + t K grows with t / h²: at a base scale of 60 edges on a 1 M-face mesh that is
// 400 iterations, and CHOLMOD's factorization of the whole system costs as much. What those
// iterations spend their time on is the smooth part of the error, which a coarse copy of the system
// represents with a fraction of the unknowns. So the preconditioner is the two-grid cycle of
// aggregation-based algebraic multigrid (Vaněk, Mandel, Brezina 1996; Notay 2010), built from the
// matrix alone:
//   - aggregates: greedy, each a vertex with its still-free neighbours (the matrix graph is the
//     mesh's edge graph), left-over vertices joining the neighbouring aggregate they are most
//     strongly coupled to — about 1/8 of the unknowns;
//   - prolongation P: the aggregates' indicators (piecewise constant). Two variants were tried
//     while writing this and not kept (so not in the benchmarks): smoothing P by a Jacobi step, as
//     smoothed aggregation does, saved 3 of 17 iterations at 60 edges but made the set-up about
//     3x dearer; a second round of aggregation (1/70 of the unknowns) doubled the iterations;
//   - coarse operator Pᵀ A P (Galerkin: the couplings summed aggregate by aggregate), factorized
//     once by CHOLMOD;
//   - cycle: damped Jacobi, coarse correction, damped Jacobi — symmetric, so it is a valid
//     preconditioner for conjugate gradients.
// On the 1 M-face relief torus: 11, 17 and 21 iterations at 15, 60 and 227 edge lengths, where
// Jacobi-preconditioned conjugate gradients take 131, 391 and over 1,000.
// Measured figures (iterations, time, angle to the exact solve): bench/bench_solvers, docs/benchmarks.md.
#pragma once

#include <Eigen/Sparse>
#include <memory>

namespace reliefkit {

/// The two-grid cycle for one SPD matrix (both triangles stored). Building it fails (ok() false)
/// when the coarse factorization does; preconditioned_cg() then must not be given it.
class TwoLevelPreconditioner {
 public:
  explicit TwoLevelPreconditioner(const Eigen::SparseMatrix<double>& A);
  ~TwoLevelPreconditioner();
  bool ok() const;
  int coarse_size() const;
  struct Parts;  // the matrix, smoother, aggregates and coarse factorization (multilevel.cpp)
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
int preconditioned_cg(const TwoLevelPreconditioner& preconditioner, const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
                      double tolerance, int max_iterations);

}  // namespace reliefkit
