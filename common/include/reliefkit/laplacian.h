// ReliefKit — cotangent Laplacian and mixed Voronoi mass matrix.
//
// L is #V x #V, symmetric, L_ij = (cot alpha_ij + cot beta_ij) / 2 for an edge ij (the angles
// opposite the edge in its one or two faces), L_ii = -sum_j L_ij: negative semi-definite, rows
// sum to zero, L * f = 0 for f linear on a flat region (Pinkall & Polthier 1993; Meyer et al.
// 2003). M is diagonal with the mixed Voronoi areas, so M^-1 L f approximates the
// Laplace-Beltrami operator of f (for f = x^2 + y^2 on a plane: 4). Degenerate faces contribute
// nothing (their cotangents are not finite) and are counted.
#pragma once

#include <Eigen/Sparse>

#include "reliefkit/mesh.h"

namespace reliefkit {

struct LaplacianResult {
  Eigen::SparseMatrix<double> L;     // cotangent Laplacian (stiffness), #V x #V
  Eigen::SparseMatrix<double> M;     // diagonal mixed-Voronoi mass matrix, #V x #V
  long long degenerate_faces = 0;
};

LaplacianResult cotangent_laplacian(const TriMesh& mesh);

}  // namespace reliefkit
