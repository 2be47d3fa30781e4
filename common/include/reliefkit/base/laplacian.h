// ReliefKit — cotangent Laplacian and mixed Voronoi mass matrix.
//
// L is #V x #V, symmetric, L_ij = (cot alpha_ij + cot beta_ij) / 2 for an edge ij (the angles
// opposite the edge in its one or two faces), L_ii = -sum_j L_ij: negative semi-definite, rows
// sum to zero, L * f = 0 for f linear on a flat region (Pinkall & Polthier 1993; Meyer et al.
// 2003). M is diagonal with the mixed Voronoi areas, so M^-1 L f approximates the
// Laplace-Beltrami operator of f (for f = x^2 + y^2 on a plane: 4). Degenerate faces contribute
// nothing (their cotangents are not finite) and are counted.
//
// Assembly is row by row in parallel, straight into compressed storage (every row holds its
// diagonal, columns sorted), in time linear in the face count even around a vertex of very high
// valence. Being symmetric, L is equally its own row-major view (reliefkit/base/solvers.h uses that).
#pragma once

#include <Eigen/Sparse>

#include "reliefkit/base/mesh.h"

namespace reliefkit {

struct LaplacianResult {
  Eigen::SparseMatrix<double> L;     // cotangent Laplacian (stiffness), #V x #V
  Eigen::VectorXd mass;              // mixed Voronoi area per vertex (the diagonal of M)
  Eigen::SparseMatrix<double> M;     // the same as a diagonal sparse matrix
  long long degenerate_faces = 0;    // zero-area faces and slivers (kSliverAreaRatio), left out of L
};

/// A face whose doubled area is below this share of its longest edge squared (a sliver: its
/// cotangents reach 1 / this) is left out of the stiffness like a zero-area face. The weights of
/// a sliver are large differences of large numbers: their sum of products, 1 for every triangle,
/// comes out negative in rounding and the Laplacian is no longer semi-definite. Measured on the
/// oxhide ingot scan: the scale space folded a few faces into slivers (ratio 2e-12 at σ = 4 edge
/// lengths); the next level's system was not positive definite, conjugate gradients diverged and
/// every vertex moved 10^13 edge lengths. Faces this thin carry no area worth the error.
constexpr double kSliverAreaRatio = 1e-7;

struct LaplacianOptions {
  /// Negative cotangent weights (obtuse triangles) set to zero: L stays an M-matrix, so a heat
  /// step (M - t L) x = M b keeps a maximum principle on poor triangulations.
  bool clamp_negative = false;
};

/// `topology`: its faces and ring are used (the border is not needed).
LaplacianResult cotangent_laplacian(const TriMesh& mesh, const MeshTopology& topology, const LaplacianOptions& options = {});
LaplacianResult cotangent_laplacian(const TriMesh& mesh, const LaplacianOptions& options = {});

/// The uniform (graph) Laplacian L = I - D^-1 A over the ring's neighbours (the Laplacian
/// coordinates of the thesis' eq. 7.7): row i holds 1 on the diagonal and -1/d_i for each of its d_i
/// neighbours; a vertex without neighbours has an empty row. Not symmetric (rows sum to zero).
Eigen::SparseMatrix<double> uniform_laplacian(const VertexRing& ring);

}  // namespace reliefkit
