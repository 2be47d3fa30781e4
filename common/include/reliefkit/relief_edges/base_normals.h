// ReliefKit — normals of the smooth base surface under a relief (thesis section 4.4).
//
// The thesis smooths the surface normals with an adaptive Gaussian three times wider than the
// local feature; it took 16 s for 50 K vertices. Here the normals are diffused over the surface
// by one implicit (backward Euler) heat step, (M + t K) X = M N with t = scale^2 / 2 — the
// heat kernel's spread at that time is a Gaussian of standard deviation `scale` — where M holds
// the mixed Voronoi areas and K the cotangent stiffness (negative cotangent weights clamped to
// zero, which keeps the system an M-matrix on poor triangulations). The system is solved by the
// shared solver (reliefkit/base/solvers.h): Eigen's conjugate gradients started from the surface
// normals, or CHOLMOD's Cholesky factorization when the scale is so many edges wide that conjugate
// gradients would need more time than the factorization (measured crossover: about 50 edges at
// 1 M faces; docs/reliability.md), each falling back to the other when it fails.
// Diffusing over the surface (not in space) keeps the two sides of a thin object apart.
#pragma once

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/scale.h"
#include "reliefkit/base/solvers.h"
#include "reliefkit/base/surface.h"

namespace reliefkit {

struct BaseNormalOptions {
  double scale = 0;          // Gaussian scale in mesh units (required, > 0)
  int max_iterations = 1000;  // conjugate-gradient limit (per coordinate)
  double tolerance = 1e-3;    // relative residual asked of the solve
  SolverMethod method = SolverMethod::Auto;
  Progress progress = nullptr;
};

struct BaseNormals {
  std::vector<Vec3> normal;  // #V unit base normals
  SolveReport solve;         // which solver, iterations, the residual measured on the result
  double expected_iterations = 0;  // conjugate-gradient iterations predicted from the conditioning
};

/// Base normals from the surface normals (one per vertex, e.g. Curvature::normal).
BaseNormals estimate_base_normals(const Surface& surface, const std::vector<Vec3>& surface_normals,
                                  const BaseNormalOptions& options);
BaseNormals estimate_base_normals(const TriMesh& mesh, const std::vector<Vec3>& surface_normals,
                                  const BaseNormalOptions& options);

/// The base scale without curvature at hand (mesh units): kDefaultBaseScaleEdges edge lengths.
/// Relief Edges also takes it at least kBaseScaleWidths x the features' own width.
constexpr double kDefaultBaseScaleEdges = 15.0;
double automatic_base_scale(const MeshScale& scale);
/// automatic_base_scale of the mesh.
double default_base_scale(const TriMesh& mesh);

}  // namespace reliefkit
