// ReliefKit — per-vertex curvature and curvature derivatives.
//
// Two estimators (CurvatureEstimator): the default fits a cubic jet at every vertex (see below);
// the alternative is S. Rusinkiewicz, "Estimating Curvatures and Their Derivatives on Triangle Meshes",
// 3DPVT 2004 (thesis ref. [111]). Per face, the second fundamental form II is fitted by least
// squares to the differences of the vertex normals along the three edges; each face's II is
// rotated into the frame of each of its vertices and averaged with mixed-Voronoi corner-area
// weights. The derivative tensor C (thesis eq. 3.1) is fitted the same way to the differences
// of the per-vertex II along the edges. Normals use N. Max's weights (1999), exact on spheres.
//
// Conventions
//  * Normals point outwards (counter-clockwise faces). Curvature is positive where the surface
//    bends away from its normal: a sphere of radius r has k1 = k2 = +1/r; the crest of a raised
//    relief is positive, the bottom of an engraved line negative.
//  * k1 >= k2 (signed order): dir1 is the direction of maximal curvature, dir2 = normal x dir1.
//  * The derivative tensor is expressed in the (dir1, dir2) frame of its vertex:
//      C(v,v,v) = a v1^3 + 3 b v1^2 v2 + 3 c v1 v2^2 + d v2^3,   v = v1 dir1 + v2 dir2,
//    i.e. the derivative along v of the normal curvature in direction v (thesis eq. 3.3).
//    Flipping dir1 flips the signs of a and c; flipping dir2 those of b and d.
//  * Units: curvature is 1/length and C is 1/length^2 in the mesh's units.
#pragma once

#include <memory>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/scale.h"
#include "reliefkit/base/surface.h"

namespace reliefkit {

struct CurvatureDerivative {
  double a = 0, b = 0, c = 0, d = 0;
  /// C(v,v,v) for v = (v1, v2) in the vertex's principal frame.
  double along(double v1, double v2) const {
    return a * v1 * v1 * v1 + 3 * b * v1 * v1 * v2 + 3 * c * v1 * v2 * v2 + d * v2 * v2 * v2;
  }
};

enum class CurvatureEstimator {
  /// Per-vertex osculating jet: least-squares cubic height function over the tangent plane,
  /// fitted to the two-ring (Cazals & Pouget 2003, thesis ref. [76]; Goldfeather & Interrante
  /// [42] fit cubics too). Second-order accurate on irregular meshes. Default.
  Jet,
  /// Per-face fit of II and C to normal / curvature differences, averaged at the vertices
  /// (Rusinkiewicz 2004, ref. [111]). Faster, but on irregular triangulations its error does
  /// not fall with refinement (see tests).
  FaceFit,
};

struct CurvatureOptions {
  CurvatureEstimator estimator = CurvatureEstimator::Jet;
  /// Gaussian scale (mesh units) of a diffusion of the vertex positions (on a copy) before the
  /// estimate; it suppresses scanner noise finer than the scale. Results stay attached to the
  /// original vertices; normals and areas are those of the smoothed copy. 0 = no smoothing.
  double smoothing_scale = 0;
  /// Also estimate the derivative tensor (the second pass roughly doubles the time).
  bool derivatives = true;
  Progress progress = nullptr;
};

struct Curvature {
  std::vector<Vec3> normal;         // #V unit normals (Max's weights, smoothed if asked)
  std::vector<Vec3> dir1, dir2;     // #V unit principal directions, tangent, dir1 x dir2 = normal
  std::vector<double> k1, k2;       // #V principal curvatures, k1 >= k2
  std::vector<CurvatureDerivative> dcurv;  // #V derivative tensor in (dir1, dir2); empty if not asked
  std::vector<double> point_area;   // #V mixed Voronoi area (sum = surface area)
  std::vector<int> bad_vertices;    // vertices without any usable face: zero curvature, arbitrary frame
  long long degenerate_faces = 0;   // faces of zero area or with non-finite geometry, skipped

  /// Normal curvature k(t) = t^T II t for a tangent direction t (need not be unit or exactly tangent).
  double normal_curvature(int v, const Vec3& t) const;
  /// C(t,t,t) for a tangent direction t, normalised to unit length in the tangent plane.
  double derivative_along(int v, const Vec3& t) const;
  double mean(int v) const { return 0.5 * (k1[v] + k2[v]); }
  double gaussian(int v) const { return k1[v] * k2[v]; }
};

/// Computes normals, point areas, principal curvatures/directions and (optionally) the
/// derivative tensor at every vertex. Throws InputError for meshes require_triangles rejects.
/// Runs in parallel (OpenMP) over faces and vertices; no result is NaN. The surface's run gives
/// the connectivity and the pre-smoothing's number of steps; the smoothed copy is
/// surface.with_positions(...) (smoothed_surface).
Curvature compute_curvature(const Surface& surface, const CurvatureOptions& options = {});
/// The same on a mesh with no run yet (its connectivity and scale are computed here).
Curvature compute_curvature(const TriMesh& mesh, const CurvatureOptions& options = {});

/// The first stage of every curve filter: the scan's scale and noise level, the pre-smoothing
/// they give ("auto") or the user's multiple of the edge length, and the curvature with
/// derivatives at that scale.
struct ScaledCurvature {
  std::shared_ptr<const MeshTopology> topology;  // built once, for the later stages too
  MeshScale scale;
  NoiseEstimate noise;
  double presmoothing = 0;  // used, mesh units
  /// Of the pre-smoothed surface (Surface::curvature of smoothed_surface(surface, presmoothing)),
  /// shared with the run's Surface when there is no pre-smoothing.
  std::shared_ptr<const Curvature> curvature;
};
/// The surface's topology, scale and noise come from the run's Surface (computed there once).
ScaledCurvature curvature_at_scale(const Surface& surface, const Length& presmoothing, CurvatureEstimator estimator,
                                   Progress progress);
ScaledCurvature curvature_at_scale(const TriMesh& mesh, const Length& presmoothing, CurvatureEstimator estimator,
                                   Progress progress);

/// The start every curve filter shares: its parameters checked (Params::validate), the mesh
/// checked, then curvature_at_scale with the parameters' pre-smoothing, estimator and progress.
template <class Params>
ScaledCurvature begin_curve_filter(const Surface& surface, const Params& params) {
  params.validate();
  return curvature_at_scale(surface, params.presmoothing, params.estimator, params.progress);
}

/// The width of the surface's features (mesh units), from the curvature itself: the ratio of the
/// 99th percentiles of |curvature| (max |k1|, |k2|) and of the size of the derivative tensor C
/// over the vertices that count and are not on a boundary. For a smoothed step of width w
/// (profile tanh(x / w)) it is about 0.75 w whatever the mesh resolution and unit (measured on the
/// cylinder relief at 100 K, 1 M and 4 M faces: 0.029, 0.030, 0.030 for w = 0.04). 0 if the mesh
/// has no curvature derivative.
double feature_width(const TriMesh& mesh, const Curvature& curvature, const MeshScale& scale,
                     const MeshTopology* topology = nullptr);

/// Unit vertex normals by Max's weights (exact for vertices on a sphere). Vertices without a
/// usable face get (0,0,1).
std::vector<Vec3> vertex_normals(const TriMesh& mesh, const VertexFaces& vf);

/// Mixed Voronoi area of each face corner (Meyer et al. 2003), #F x 3; sums to face areas.
std::vector<std::array<double, 3>> corner_areas(const TriMesh& mesh);

}  // namespace reliefkit
