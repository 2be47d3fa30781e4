// ReliefKit — the geometry of one run, computed once and shared by every stage of it.
//
// A filter run repairs its copy of the layer, then hands a Surface to the cores. What never
// changes during the run — the connectivity (vertex-face adjacency, rings, border), the scan's
// scale (edge length, parts) and its noise level — is computed on first request and then kept;
// what depends on the positions — normals, the cotangent Laplacian with its mass matrix, and the
// curvature (curvature.h) — is kept per set of positions. A stage that moves the vertices (pre-smoothing, a scale-space level,
// a deformation) asks for `with_positions(p)`: a Surface that shares the run's connectivity, scale
// and noise with its origin but computes its own position-dependent data, so a change of
// positions can never serve a stale Laplacian (the idea of geometry-central's require*()).
//
// Requests are lazy, computed at most once, and safe from several threads.
#pragma once

#include <memory>

#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/mesh.h"
#include "reliefkit/base/scale.h"

namespace reliefkit {

struct Curvature;
enum class CurvatureEstimator;

class Surface {
 public:
  /// `mesh` must be ready for computation (require_triangles accepts it; repaired if need be).
  /// `faces`: its vertex-face adjacency when the caller built it already (the repair does).
  explicit Surface(TriMesh mesh, VertexFaces faces = {});
  /// A Surface over a mesh the caller keeps alive for the Surface's lifetime (no copy).
  static Surface borrow(const TriMesh& mesh, VertexFaces faces = {});

  const TriMesh& mesh() const { return *mesh_; }
  int n_vertices() const { return mesh_->n_vertices(); }
  int n_faces() const { return mesh_->n_faces(); }
  /// require_triangles() on the mesh, checked once per run (every stage may ask; a refusal is
  /// thrown again on every ask).
  void require_triangles() const;

  // Of the run (the same for every Surface made from this one by with_positions).
  const MeshTopology& topology() const;
  std::shared_ptr<const MeshTopology> shared_topology() const;
  const MeshScale& scale() const;
  /// The noise estimate of the run's input positions. Throws InputError when the mesh has no
  /// usable edge length (nothing to measure against).
  const NoiseEstimate& noise() const;

  // Of these positions.
  const std::vector<Vec3>& normals() const;
  const LaplacianResult& laplacian(const LaplacianOptions& options = {}) const;
  /// The curvature at these positions (no smoothing: a smoothed surface is with_positions of its
  /// own), with the derivative tensor if asked; a result with derivatives also serves a request
  /// without. Shared: it stays valid after the Surface is gone.
  std::shared_ptr<const Curvature> curvature(CurvatureEstimator estimator, bool derivatives,
                                             Progress progress = nullptr) const;

  /// The same surface at other positions (one per vertex).
  Surface with_positions(std::vector<Vec3> positions) const;

 private:
  struct Run;        // connectivity, scale, noise
  struct Positions;  // normals, Laplacians
  Surface(std::shared_ptr<const TriMesh> mesh, std::shared_ptr<Run> run);
  std::shared_ptr<const TriMesh> mesh_;
  std::shared_ptr<Run> run_;
  std::shared_ptr<Positions> at_;
};

/// Throws InputError unless the scale has a usable edge length (positive, finite).
void require_usable_scale(const MeshScale& scale);

}  // namespace reliefkit
