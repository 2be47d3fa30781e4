#include "reliefkit/laplacian.h"

#include <cmath>

#include "reliefkit/curvature.h"

namespace reliefkit {

LaplacianResult cotangent_laplacian(const TriMesh& mesh) {
  LaplacianResult r;
  const int nv = mesh.n_vertices();
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(mesh.faces.size() * 12);
  for (const auto& f : mesh.faces) {
    double cot[3];
    bool ok = true;
    for (int j = 0; j < 3; ++j) {  // angle at corner j, opposite edge (j+1, j+2)
      Vec3 a = mesh.vertices[f[(j + 1) % 3]] - mesh.vertices[f[j]];
      Vec3 b = mesh.vertices[f[(j + 2) % 3]] - mesh.vertices[f[j]];
      double s = a.cross(b).norm();
      cot[j] = a.dot(b) / s;
      if (!(s > 0) || !std::isfinite(cot[j])) ok = false;
    }
    if (!ok) {
      ++r.degenerate_faces;
      continue;
    }
    for (int j = 0; j < 3; ++j) {
      int p = f[(j + 1) % 3], q = f[(j + 2) % 3];
      double w = 0.5 * cot[j];
      trip.emplace_back(p, q, w);
      trip.emplace_back(q, p, w);
      trip.emplace_back(p, p, -w);
      trip.emplace_back(q, q, -w);
    }
  }
  r.L.resize(nv, nv);
  r.L.setFromTriplets(trip.begin(), trip.end());
  auto ca = corner_areas(mesh);
  Eigen::VectorXd area = Eigen::VectorXd::Zero(nv);
  for (size_t i = 0; i < mesh.faces.size(); ++i)
    for (int j = 0; j < 3; ++j) area[mesh.faces[i][j]] += ca[i][j];
  r.M.resize(nv, nv);
  std::vector<Eigen::Triplet<double>> diag;
  diag.reserve(nv);
  for (int v = 0; v < nv; ++v) diag.emplace_back(v, v, area[v]);
  r.M.setFromTriplets(diag.begin(), diag.end());
  return r;
}

}  // namespace reliefkit
