#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Eigenvalues>

#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/smoothing.h"
#include "shapes.h"

using namespace reliefkit;

TEST(Laplacian, SymmetricRowsSumToZeroAndLinearPrecision) {
  TriMesh m = rktest::height_field([](double, double) { return 0.0; }, 1.0, 30, 0.4, 3);
  LaplacianResult r = cotangent_laplacian(m);
  Eigen::SparseMatrix<double> asym = r.L - Eigen::SparseMatrix<double>(r.L.transpose());
  EXPECT_LT(asym.norm(), 1e-10);
  Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.n_vertices());
  EXPECT_LT((r.L * ones).cwiseAbs().maxCoeff(), 1e-10);
  Eigen::VectorXd lin(m.n_vertices()), quad(m.n_vertices());
  for (int i = 0; i < m.n_vertices(); ++i) {
    lin[i] = 2 * m.vertices[i].x() - 3 * m.vertices[i].y();
    quad[i] = m.vertices[i].squaredNorm();
  }
  Eigen::VectorXd Llin = r.L * lin, Lq = r.L * quad;
  std::vector<double> lap;
  for (int i = 0; i < m.n_vertices(); ++i) {
    const Vec3& p = m.vertices[i];
    if (std::abs(p.x()) > 0.9 || std::abs(p.y()) > 0.9) continue;  // interior only
    EXPECT_NEAR(Llin[i], 0, 1e-9);
    lap.push_back(Lq[i] / r.M.coeff(i, i));
  }
  // Laplacian of x^2 + y^2 is 4: pointwise it is only approximate on an irregular mesh.
  EXPECT_NEAR(rktest::median(lap), 4.0, 0.2);
  EXPECT_NEAR(r.M.sum(), 4.0, 1e-9);  // mixed areas sum to the surface area
  // Negative semi-definite.
  EXPECT_LE(quad.dot(r.L * quad), 1e-12);
}

// A sliver's cotangents are huge differences of huge numbers; in rounding they left the Laplacian
// indefinite (the oxhide ingot's scale space diverged). A sliver adds nothing to the stiffness.
TEST(Laplacian, ASliverFaceIsLeftOutOfTheStiffness) {
  TriMesh m;
  // Triangle A B D split at C, which lies 1e-9 off the edge AB: face ABC is a sliver.
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1e-9, 0), Vec3(0.5, 1, 0)};
  m.faces = {{0, 1, 2}, {1, 3, 2}, {2, 3, 0}};
  const LaplacianResult r = cotangent_laplacian(m);
  EXPECT_EQ(r.degenerate_faces, 1);
  EXPECT_EQ(r.L.coeff(0, 1), 0.0);  // edge AB lies only in the sliver (its weight was -2.5e8)
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(-Eigen::MatrixXd(r.L));
  EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-9);
}

TEST(Laplacian, SphereMeanCurvatureNormal) {
  // Delta x = -2 H n: on the unit sphere M^-1 L x = -2 x.
  TriMesh m = rktest::sphere(1.0, 4);
  LaplacianResult r = cotangent_laplacian(m);
  Eigen::MatrixXd X(m.n_vertices(), 3);
  for (int i = 0; i < m.n_vertices(); ++i) X.row(i) = m.vertices[i].transpose();
  Eigen::MatrixXd LX = r.L * X;
  std::vector<double> err;
  for (int i = 0; i < m.n_vertices(); ++i) err.push_back((LX.row(i) / r.M.coeff(i, i) + 2 * X.row(i)).norm());
  EXPECT_LT(rktest::median(err), 0.01);
}

TEST(Smoothing, DiffusionSpreadsLikeAGaussianOfTheGivenScale) {
  const int n = 120;
  TriMesh m = rktest::height_field([](double, double) { return 0.0; }, 1.0, n);
  const Surface surface = Surface::borrow(m);
  std::vector<double> f(m.n_vertices(), 0.0);
  int center = (n / 2) * (n + 1) + n / 2;
  ASSERT_NEAR(m.vertices[center].norm(), 0, 1e-12);
  f[center] = 1.0;
  const double sigma = 0.08;  // ~5 grid cells
  diffuse(surface, sigma, f);
  double mass = 0, vx = 0, vy = 0;
  for (int i = 0; i < m.n_vertices(); ++i) {
    mass += f[i];
    vx += f[i] * m.vertices[i].x() * m.vertices[i].x();
    vy += f[i] * m.vertices[i].y() * m.vertices[i].y();
  }
  ASSERT_GT(mass, 0.5);
  const double spread = std::sqrt(0.5 * (vx + vy) / mass);
  std::printf("diffusion of scale %.4f: measured spread %.4f (%.2f %% off)\n", sigma, spread,
              100 * std::abs(spread / sigma - 1));
  EXPECT_NEAR(spread, sigma, 0.03 * sigma);  // measured 0.7 %
  EXPECT_EQ(diffusion_steps(surface.scale(), 0), 0);
  std::vector<double> constant(m.n_vertices(), 2.5);
  diffuse(surface, sigma, constant);
  for (double c : constant) ASSERT_NEAR(c, 2.5, 1e-12);
}
