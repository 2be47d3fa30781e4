// The shared pieces the base deformation (thesis sect. 7.5) stands on, with known answers: a mesh's
// edges with their faces (reliefkit/base/mesh.h), the uniform Laplacian of eq. 7.7
// (reliefkit/base/laplacian.h), and a Cholesky factorization kept across solves
// (reliefkit/base/solvers.h: ordered once, factorized again only when the values change).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/solvers.h"
#include "reliefkit/base/work_counts.h"

using namespace reliefkit;

namespace {
// Two triangles sharing edge 1-2, and a fifth vertex no face uses.
TriMesh two_triangles() {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(5, 5, 5)};
  m.faces = {{0, 1, 2}, {1, 3, 2}};
  return m;
}

Eigen::SparseMatrix<double> tridiagonal(int n, double diagonal) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, diagonal);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}
}  // namespace

TEST(MeshEdges, EachEdgeOnceWithItsFaces) {
  const TriMesh m = two_triangles();
  const auto edges = mesh_edges(m, vertex_faces(m));
  ASSERT_EQ(edges.size(), 5u);
  const int expect[5][5] = {{0, 1, 1, 0, -1}, {0, 2, 1, 0, -1}, {1, 2, 2, 0, 1}, {1, 3, 1, 1, -1}, {2, 3, 1, 1, -1}};
  for (size_t k = 0; k < edges.size(); ++k) {
    EXPECT_EQ(edges[k].a, expect[k][0]) << k;
    EXPECT_EQ(edges[k].b, expect[k][1]) << k;
    EXPECT_EQ(edges[k].faces, expect[k][2]) << k;
    EXPECT_EQ(edges[k].face[0], expect[k][3]) << k;
    EXPECT_EQ(edges[k].face[1], expect[k][4]) << k;
  }
}

TEST(MeshEdges, ANonManifoldEdgeCountsAllItsFacesAndKeepsTheFirstTwo) {
  TriMesh m = two_triangles();
  m.faces.push_back({2, 1, 4});  // a third face on edge 1-2
  const auto edges = mesh_edges(m, vertex_faces(m));
  const auto e = std::find_if(edges.begin(), edges.end(), [](const MeshEdge& x) { return x.a == 1 && x.b == 2; });
  ASSERT_NE(e, edges.end());
  EXPECT_EQ(e->faces, 3);
  EXPECT_EQ(e->face[0], 0);
  EXPECT_EQ(e->face[1], 1);
}

TEST(UniformLaplacian, IdentityMinusTheMeanOfTheNeighbours) {
  const TriMesh m = two_triangles();
  const VertexRing ring = vertex_rings(m, vertex_faces(m));
  const long long before = work_counts()[Work::Laplacian];
  const Eigen::SparseMatrix<double> L = uniform_laplacian(ring);
  EXPECT_EQ(work_counts()[Work::Laplacian], before + 1);
  const Eigen::MatrixXd D = Eigen::MatrixXd(L);
  Eigen::MatrixXd expect(5, 5);
  expect << 1, -0.5, -0.5, 0, 0,                      //
      -1. / 3, 1, -1. / 3, -1. / 3, 0,                 //
      -1. / 3, -1. / 3, 1, -1. / 3, 0,                 //
      0, -0.5, -0.5, 1, 0,                             //
      0, 0, 0, 0, 0;                                   // no neighbours: an empty row
  EXPECT_LT((D - expect).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(L.nonZeros(), 3 + 4 + 4 + 3);  // vertex 4's row and column hold nothing, not even zeros
  // The Laplacian coordinates of vertex 0: itself minus the mean of 1 and 2.
  Eigen::MatrixXd V(5, 3);
  for (int i = 0; i < 5; ++i) V.row(i) = m.vertices[size_t(i)].transpose();
  EXPECT_LT(((L * V).row(0) - Eigen::RowVector3d(-0.5, -0.5, 0)).norm(), 1e-15);
}

TEST(SpdFactorization, KeptWhileTheMatrixIsTheSameOrderedOncePerPattern) {
  const int n = 50;
  const Eigen::SparseMatrix<double> A = tridiagonal(n, 3);
  Eigen::MatrixXd x_true(n, 2);
  for (int i = 0; i < n; ++i) x_true(i, 0) = i, x_true(i, 1) = std::sin(i);
  const Eigen::MatrixXd B = A * x_true;
  SpdFactorization f;
  Eigen::MatrixXd X;
  SolveReport r = solve_spd(A, B, X, f);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.method, "Cholesky (CHOLMOD)");
  EXPECT_LT((X - x_true).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(r.residual, 1e-14);
  // The same matrix again (another right-hand side): the factorization is kept.
  solve_spd(A, 2 * B, X, f);
  EXPECT_LT((X - 2 * x_true).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(f.factorizations(), 1);
  EXPECT_EQ(f.orderings(), 1);
  // Other values on the same pattern: factorized again, not ordered again.
  const Eigen::SparseMatrix<double> A4 = tridiagonal(n, 4);
  r = solve_spd(A4, A4 * x_true, X, f);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((X - x_true).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(f.factorizations(), 2);
  EXPECT_EQ(f.orderings(), 1);
  // Another pattern: ordered again.
  const Eigen::SparseMatrix<double> I = tridiagonal(n + 1, 5);
  solve_spd(I, Eigen::MatrixXd::Ones(n + 1, 1), X, f);
  EXPECT_EQ(f.orderings(), 2);
  EXPECT_EQ(f.factorizations(), 3);
}

TEST(SpdFactorization, AMatrixNotPositiveDefiniteIsReportedNotThrown) {
  const Eigen::SparseMatrix<double> A = tridiagonal(10, -3);
  SpdFactorization f(SpdFactorization::Ordering::Best);
  Eigen::MatrixXd X;
  SolveReport r;
  EXPECT_NO_THROW(r = solve_spd(A, Eigen::MatrixXd::Ones(10, 1), X, f));
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.note.find("factorization failed"), std::string::npos) << r.note;
  EXPECT_EQ(f.factorizations(), 1);
  // A failed factorization is not kept: the same matrix is factorized again, and fails again.
  r = solve_spd(A, Eigen::MatrixXd::Ones(10, 1), X, f);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(f.factorizations(), 2);
  EXPECT_THROW(solve_spd(A, Eigen::MatrixXd::Ones(9, 1), X, f), InputError);
}
