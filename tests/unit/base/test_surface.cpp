// The per-run geometry context: computed once, shared by the stages, never stale after a change of
// positions; the repair's adjacency is the one a fresh build gives.
#include <gtest/gtest.h>

#include "reliefkit/base/memory.h"
#include "reliefkit/base/curvature.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/base/repair.h"
#include "reliefkit/relief_edges/ridges.h"
#include "reliefkit/base/surface.h"
#include "reliefkit/base/work_counts.h"
#include "shapes.h"

using namespace reliefkit;

TEST(Surface, TwoCoresOnOneSurfaceBuildTheScansGeometryOnce) {
  const TriMesh m = rktest::torus(2, 0.7, 60, 30, 0.1);
  const Surface s = Surface::borrow(m);
  reset_work_counts();
  RidgeValleyParams rp;
  rp.presmoothing = Length::in_edges(1);
  compute_ridges_valleys(s, rp);
  compute_ridges_valleys(s, rp);
  ReliefEdgeParams ep;
  ep.presmoothing = Length::in_edges(1);
  compute_relief_edges(s, ep);
  compute_relief_edges(s, ep);
  const WorkCounts c = work_counts();
  // The relief edges' noise-floor simulation runs on its own small patch (its adjacency, scale and
  // noise are counted too): once per call.
  EXPECT_EQ(c[Work::NoiseFloor], 2);
  EXPECT_EQ(c[Work::Adjacency], 1 + c[Work::NoiseFloor]) << c.summary();
  EXPECT_EQ(c[Work::MeshScale], 1 + c[Work::NoiseFloor]) << c.summary();
  EXPECT_EQ(c[Work::Noise], 1 + c[Work::NoiseFloor]) << c.summary();
  EXPECT_EQ(c[Work::Laplacian], 1) << c.summary();  // the base normals' system, shared by both calls
}

TEST(Surface, NewPositionsShareTheRunButNotThePositionsData) {
  const TriMesh m = rktest::sphere(1, 3);
  const Surface s(m);
  const LaplacianResult& l1 = s.laplacian();
  std::vector<Vec3> doubled = m.vertices;
  for (auto& p : doubled) p *= 2;
  const Surface t = s.with_positions(doubled);
  EXPECT_EQ(&s.topology(), &t.topology());
  EXPECT_EQ(&s.scale(), &t.scale());
  const LaplacianResult& l2 = t.laplacian();
  EXPECT_NE(&l1, &l2);
  // The cotangent weights do not change with a uniform scaling; the Voronoi areas grow 4 times.
  EXPECT_NEAR((l2.L - l1.L).norm(), 0, 1e-9 * l1.L.norm());
  EXPECT_NEAR(l2.mass.sum(), 4 * l1.mass.sum(), 1e-9 * l1.mass.sum());
  EXPECT_NEAR(t.normals()[0].norm(), 1, 1e-12);
  EXPECT_THROW(s.with_positions({Vec3::Zero()}), InputError);
}

TEST(Surface, CurvatureIsComputedOncePerPositions) {
  const TriMesh m = rktest::sphere(1, 3);
  const Surface s = Surface::borrow(m);
  reset_work_counts();
  const auto with_derivatives = s.curvature(CurvatureEstimator::Jet, true);
  EXPECT_EQ(s.curvature(CurvatureEstimator::Jet, true), with_derivatives);
  EXPECT_EQ(s.curvature(CurvatureEstimator::Jet, false), with_derivatives);  // served by the fuller one
  EXPECT_EQ(curvature_at_scale(s, Length::in_edges(0), CurvatureEstimator::Jet, nullptr).curvature, with_derivatives);
  EXPECT_EQ(work_counts()[Work::Curvature], 1) << work_counts().summary();
  EXPECT_NE(s.curvature(CurvatureEstimator::FaceFit, false), with_derivatives);  // another estimator
  std::vector<Vec3> doubled = m.vertices;
  for (auto& p : doubled) p *= 2;
  const auto moved = s.with_positions(doubled).curvature(CurvatureEstimator::Jet, false);
  EXPECT_EQ(work_counts()[Work::Curvature], 3) << work_counts().summary();
  // The sphere's curvature, 1 at its positions and 1/2 at twice them: never the other's.
  EXPECT_NEAR(with_derivatives->k1[0], 1.0, 0.05);
  EXPECT_NEAR(moved->k1[0], 0.5, 0.025);
}

TEST(Surface, RepairHandsOverTheAdjacencyOfTheRepairedMesh) {
  // A sphere with faces turned, a vertex repeated per face in part (welded) and a face twice.
  TriMesh m = rktest::sphere(1, 3);
  for (size_t f = 0; f < m.faces.size(); f += 7) std::swap(m.faces[f][1], m.faces[f][2]);
  m.faces.push_back(m.faces[3]);
  const int extra = m.n_vertices();
  m.vertices.push_back(m.vertices[m.faces[10][0]]);
  m.faces[10][0] = extra;
  VertexFaces given;
  const RepairReport rep = repair_in_place(m, nullptr, &given);
  ASSERT_GT(rep.flipped_faces, 0);
  ASSERT_EQ(rep.welded_vertices, 1);
  ASSERT_EQ(rep.duplicate_faces, 1);
  const VertexFaces fresh = vertex_faces(m);
  EXPECT_EQ(given.offset, fresh.offset);
  EXPECT_EQ(given.face, fresh.face);
  EXPECT_EQ(given.corner, fresh.corner);
}

// `sized` fills new arrays of Eigen's fixed-size matrices with zeros (their default constructor
// leaves the values undefined; the compiler warned that those were read).
TEST(Memory, SizedArraysOfEigenMatricesStartAtZero) {
  std::vector<Vec3> v(3, Vec3(1, 2, 3));
  sized(v, 1000);
  std::vector<Mat3> m;
  sized(m, 1000);
  std::vector<double> d;
  sized(d, 10);
  for (const Vec3& x : v) EXPECT_EQ(x, Vec3::Zero());
  for (const Mat3& x : m) EXPECT_EQ(x, Mat3::Zero());
  for (double x : d) EXPECT_EQ(x, 0.0);
  sized(v, 4, Vec3(1, 1, 1));
  EXPECT_EQ(v.back(), Vec3(1, 1, 1));
}
