#include "reliefkit/base/surface.h"

#include <cmath>
#include <map>
#include <mutex>

#include "reliefkit/base/curvature.h"

namespace reliefkit {

struct Surface::Run {
  std::once_flag checked_once, topology_once, scale_once, noise_once;
  VertexFaces given_faces;
  std::shared_ptr<const MeshTopology> topology;
  MeshScale scale;
  NoiseEstimate noise;
};

struct Surface::Positions {
  std::once_flag normals_once;
  std::vector<Vec3> normals;
  std::mutex laplacian_mutex;
  std::map<bool, std::unique_ptr<LaplacianResult>> laplacian;  // by LaplacianOptions::clamp_negative
  std::mutex curvature_mutex;
  // By estimator, then with derivatives (true) or without.
  std::map<std::pair<CurvatureEstimator, bool>, std::shared_ptr<const Curvature>> curvature;
};

Surface::Surface(TriMesh mesh, VertexFaces faces)
    : Surface(std::make_shared<const TriMesh>(std::move(mesh)), std::make_shared<Run>()) {
  run_->given_faces = std::move(faces);
}

Surface::Surface(std::shared_ptr<const TriMesh> mesh, std::shared_ptr<Run> run)
    : mesh_(std::move(mesh)), run_(std::move(run)), at_(std::make_shared<Positions>()) {}

Surface Surface::borrow(const TriMesh& mesh, VertexFaces faces) {
  Surface s(std::shared_ptr<const TriMesh>(&mesh, [](const TriMesh*) {}), std::make_shared<Run>());
  s.run_->given_faces = std::move(faces);
  return s;
}

void Surface::require_triangles() const {
  // A throwing call leaves the flag unset, so an invalid mesh is refused on every ask.
  std::call_once(run_->checked_once, [this] { reliefkit::require_triangles(*mesh_); });
}

std::shared_ptr<const MeshTopology> Surface::shared_topology() const {
  std::call_once(run_->topology_once, [this] {
    VertexFaces& given = run_->given_faces;
    const bool usable = given.offset.size() == size_t(mesh_->n_vertices()) + 1;
    run_->topology = std::make_shared<const MeshTopology>(usable ? mesh_topology(*mesh_, std::move(given)) : mesh_topology(*mesh_));
    given = VertexFaces();
  });
  return run_->topology;
}

const MeshTopology& Surface::topology() const { return *shared_topology(); }

const MeshScale& Surface::scale() const {
  std::call_once(run_->scale_once, [this] { run_->scale = mesh_scale(*mesh_); });
  return run_->scale;
}

const NoiseEstimate& Surface::noise() const {
  require_usable_scale(scale());
  std::call_once(run_->noise_once,
                 [this] { run_->noise = estimate_noise(*mesh_, scale(), kNoiseSamples, &topology().faces); });
  return run_->noise;
}

const std::vector<Vec3>& Surface::normals() const {
  std::call_once(at_->normals_once, [this] { at_->normals = vertex_normals(*mesh_, topology().faces); });
  return at_->normals;
}

const LaplacianResult& Surface::laplacian(const LaplacianOptions& options) const {
  std::lock_guard<std::mutex> lock(at_->laplacian_mutex);
  auto& slot = at_->laplacian[options.clamp_negative];
  if (!slot) slot = std::make_unique<LaplacianResult>(cotangent_laplacian(*mesh_, topology(), options));
  return *slot;
}

std::shared_ptr<const Curvature> Surface::curvature(CurvatureEstimator estimator, bool derivatives,
                                                    Progress progress) const {
  std::lock_guard<std::mutex> lock(at_->curvature_mutex);
  if (auto full = at_->curvature.find({estimator, true}); full != at_->curvature.end()) return full->second;
  auto& slot = at_->curvature[{estimator, derivatives}];
  if (!slot) {
    CurvatureOptions options;
    options.estimator = estimator;
    options.derivatives = derivatives;
    options.progress = progress;
    slot = std::make_shared<const Curvature>(compute_curvature(*this, options));
  }
  return slot;
}

Surface Surface::with_positions(std::vector<Vec3> positions) const {
  if (positions.size() != mesh_->vertices.size())
    throw InputError("internal: new positions for " + std::to_string(positions.size()) + " vertices on a surface of " +
                     std::to_string(mesh_->vertices.size()));
  topology();  // the connectivity is the run's: build it once, before the copies share it
  auto moved = std::make_shared<TriMesh>();
  moved->faces = mesh_->faces;
  moved->vertices = std::move(positions);
  return Surface(std::move(moved), run_);
}

void require_usable_scale(const MeshScale& scale) {
  if (!(scale.edge > 0) || !std::isfinite(1 / scale.edge) || !std::isfinite(scale.object_size))
    throw InputError("the mesh has no usable edge length (its edges have zero or non-finite length): nothing to "
                     "measure. Remove degenerate faces first, e.g. Filters > Cleaning and Repairing > Remove Zero "
                     "Area Faces and Merge Close Vertices.");
}

}  // namespace reliefkit
