// Coarse copies of meshes (reliefkit/base/coarsening.h): the copy's size, its faces, and the
// interpolation that carries values back.
#include <gtest/gtest.h>

#include <cmath>

#include "reliefkit/base/coarsening.h"
#include "shapes.h"

using namespace reliefkit;

TEST(Coarsening, ATorusKeepsItsShapeInAFewThousandFaces) {
  const TriMesh fine = rktest::torus(2.0, 0.6, 240, 80, 0.2);  // 38,400 faces, jittered
  const CoarseMesh c = coarsen_mesh(fine, 6000);
  std::printf("%d faces -> %d faces, %d vertices\n", fine.n_faces(), c.mesh.n_faces(), c.mesh.n_vertices());
  EXPECT_LE(c.mesh.n_faces(), 6000);
  EXPECT_GE(c.mesh.n_faces(), 600);  // one level of aggregation: about 1/7 of the vertices each
  ASSERT_EQ(c.vertex_of.size(), fine.vertices.size());
  for (int v : c.vertex_of) ASSERT_TRUE(v >= 0 && v < c.mesh.n_vertices());
  for (const auto& f : c.mesh.faces) {
    EXPECT_TRUE(f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
    for (int v : f) ASSERT_TRUE(v >= 0 && v < c.mesh.n_vertices());
  }
  // Every coarse vertex near the torus (a mean of neighbouring vertices: inside by the sagitta of
  // an aggregate, measured 0.012 of the tube's radius at most) and the copy closed: an orientable
  // closed surface has every edge in two faces.
  for (const auto& p : c.mesh.vertices) {
    const double ring = std::hypot(p.x(), p.y()) - 2.0;
    EXPECT_NEAR(std::hypot(ring, p.z()), 0.6, 0.03);
  }
  const auto edges = mesh_edges(c.mesh, vertex_faces(c.mesh));
  int not_two = 0;
  for (const auto& e : edges) not_two += e.faces != 2;
  EXPECT_LT(not_two, int(edges.size()) / 50) << "of " << edges.size() << " edges";
}

TEST(Coarsening, InterpolationIsAPartitionOfUnityAndSmooth) {
  const TriMesh fine = rktest::torus(2.0, 0.6, 240, 80, 0.2);
  const CoarseMesh c = coarsen_mesh(fine, 6000);
  const Interpolation P = interpolation_from_coarse(fine, c);
  ASSERT_EQ(P.rows(), fine.n_vertices());
  ASSERT_EQ(P.cols(), c.mesh.n_vertices());
  // Constants carried exactly; a linear field (here x) within the curvature's error.
  const Eigen::VectorXd ones = P * Eigen::VectorXd::Ones(c.mesh.n_vertices());
  EXPECT_NEAR(ones.minCoeff(), 1.0, 1e-12);
  EXPECT_NEAR(ones.maxCoeff(), 1.0, 1e-12);
  Eigen::VectorXd x(c.mesh.n_vertices());
  for (int a = 0; a < c.mesh.n_vertices(); ++a) x[a] = c.mesh.vertices[size_t(a)].x();
  const Eigen::VectorXd carried = P * x;
  double worst = 0;
  for (int i = 0; i < fine.n_vertices(); ++i) worst = std::max(worst, std::abs(carried[i] - fine.vertices[size_t(i)].x()));
  std::printf("linear field: worst error %.4f (fine edge ~0.05)\n", worst);
  EXPECT_LT(worst, 0.08);  // measured 0.032
  // No steps: neighbouring fine vertices carry nearly the same value of a smooth coarse field.
  const auto edges = mesh_edges(fine, vertex_faces(fine));
  double jump = 0;
  for (const auto& e : edges) jump = std::max(jump, std::abs(carried[e.a] - carried[e.b]) /
                                                       (fine.vertices[size_t(e.a)] - fine.vertices[size_t(e.b)]).norm());
  std::printf("largest slope of the carried x: %.3f\n", jump);
  EXPECT_LT(jump, 2.5);  // x has slope at most 1 along the surface (measured 1.57 over the shortest jittered edges)
}

TEST(Coarsening, ASmallMeshIsItsOwnCopy) {
  const TriMesh fine = rktest::sphere(1.0, 2);
  const CoarseMesh c = coarsen_mesh(fine, 100000);
  EXPECT_EQ(c.mesh.n_faces(), fine.n_faces());
  for (int i = 0; i < fine.n_vertices(); ++i) EXPECT_EQ(c.vertex_of[size_t(i)], i);
}
