// ReliefKit — scale space of a surface: the mesh diffused to a series of Gaussian scales (thesis
// chapter 5 smooths by diffusion, after ref. [130]).
//
// Each level is reached from the previous one by heat steps of the vertex positions, implicit
// (backward Euler, (M − Δτ L) X_k = M X_{k−1}) or explicit, with L and M the cotangent Laplacian
// and mixed areas of the previous level's surface (`reweight`; the input's for the first level),
// so large scales cost sparse solves, not thousands of explicit steps.
// A Gaussian of standard deviation σ is the heat kernel at τ = σ² / 2.
// Boundaries: a vertex on a simple boundary loop diffuses only along the loop (1-D heat steps on
// the boundary polyline, edge-length weights), then the interior is solved with the boundary as
// fixed values — so an open scan does not shrink inwards from its rim and both systems stay
// symmetric positive definite. Vertices on non-manifold boundaries and isolated vertices stay
// in place. A small hole's loop contracts under the 1-D flow: its edges count as at least a tenth
// of their input length (kShortestLoopEdge in scale_space.cpp), so its system stays conditioned;
// slivers the flow folds are left out of the stiffness (kSliverAreaRatio, laplacian.h).
// The solves go through reliefkit/base/solvers.h (conjugate gradients warm-started from the previous
// level, or Cholesky for wide steps). Small scales are cheaper by explicit (forward Euler) steps
// within their stability limit — a few sparse products where an implicit step needs a solve: with
// `Stepping::Auto` each level takes whichever of the two a cost model (products per level,
// from the Gershgorin bound of M⁻¹K and the predicted conjugate-gradient iterations) says is
// cheaper. On a regular mesh that is explicit up to about 10 edge lengths and implicit above; on
// a scan with slivers (a large bound) implicit earlier. Only one set of positions is held: the visitor sees each
// level in turn and keeps what it needs (a strength per vertex, say), so memory stays bounded.
#pragma once

#include <functional>
#include <vector>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/solvers.h"
#include "reliefkit/base/surface.h"

namespace reliefkit {

struct ScaleSpaceOptions {
  enum class Stepping { Auto, Explicit, Implicit };
  Stepping stepping = Stepping::Auto;
  /// Implicit steps per doubling of the diffusion time, and at least this many per level.
  /// Backward Euler's kernel has the Gaussian's variance but a sharper peak: a Gaussian bump's
  /// height at three levels a factor 2 apart in scale is +0.5 / +1.2 / +2.5 % off with 8; the
  /// error halves with twice the steps (tests/unit/multiscale/test_scale_space.cpp).
  int substeps = 4;
  /// Re-evaluate the operator (cotangent weights, areas) on each level's surface before going on
  /// from it. An operator fixed to a noisy scan's triangles re-injects roughness at every step
  /// wherever the surface is curved: on a cylinder with 20 % noise the curvature derivative of
  /// the smoothed surface stopped falling from 4 edge lengths on (median |C| 2.5 per length², the
  /// same at 16), and t |C| grew with t.
  bool reweight = true;
  SolverMethod method = SolverMethod::Auto;
  double tolerance = 1e-4;  // relative residual of each step's displacement
  Progress progress = nullptr;
};

struct ScaleSpaceReport {
  std::vector<SolveReport> solves;  // every solve, in order
  bool converged = true;            // all of them reached their tolerance
  int boundary_vertices = 0;        // vertices diffused along their boundary loop
  int fixed_vertices = 0;           // non-manifold boundary or isolated vertices, left in place
  long long explicit_steps = 0;     // forward-Euler steps taken (each a sparse product per block)
  int implicit_steps = 0;           // backward-Euler steps taken (each a solve per block)
  std::vector<char> level_explicit; // per level: reached by explicit steps
};

using ScaleSpaceVisitor = std::function<void(int level, const Surface& smoothed)>;

/// Diffuses the surface to each Gaussian scale in `sigmas` (mesh units, increasing, > 0) and calls
/// visit(level, the surface at that scale) in order. Each level is surface.with_positions(...):
/// the run's topology, scale and noise, its own normals and Laplacian (the next level's operator
/// when `reweight`); the first step takes the input surface's Laplacian. Throws InputError for a
/// mesh without faces, scales that are not positive and increasing, or a step whose system could
/// not be solved (its residual above what a zero step leaves: never a silently wrong level).
ScaleSpaceReport scale_space(const Surface& surface, const std::vector<double>& sigmas,
                             const ScaleSpaceOptions& options, const ScaleSpaceVisitor& visit);
/// The same over a mesh of the caller's (tests, benchmarks).
ScaleSpaceReport scale_space(const TriMesh& mesh, const std::vector<double>& sigmas, const ScaleSpaceOptions& options,
                             const ScaleSpaceVisitor& visit);

}  // namespace reliefkit
