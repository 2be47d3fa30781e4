#include "reliefkit/relief_edges/base_normals.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "reliefkit/base/curvature.h"
#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/memory.h"
#include "reliefkit/base/scale.h"

namespace reliefkit {

double automatic_base_scale(const MeshScale& s) {
  return kDefaultBaseScaleEdges * s.edge;
}

double default_base_scale(const TriMesh& mesh) { return automatic_base_scale(mesh_scale(mesh)); }

namespace {

// The median of the positive vertex areas (1 when there is none).
double typical_area(const Eigen::VectorXd& mass) {
  std::vector<double> positive;
  for (Eigen::Index v = 0; v < mass.size(); ++v)
    if (mass[v] > 0) positive.push_back(mass[v]);
  if (positive.empty()) return 1.0;
  std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
  return positive[positive.size() / 2];
}

}  // namespace


BaseNormals estimate_base_normals(const TriMesh& mesh, const std::vector<Vec3>& n0, const BaseNormalOptions& opt) {
  return estimate_base_normals(Surface::borrow(mesh), n0, opt);
}

BaseNormals estimate_base_normals(const Surface& surface, const std::vector<Vec3>& n0, const BaseNormalOptions& opt) {
  const TriMesh& mesh = surface.mesh();
  surface.require_triangles();
  const int nv = mesh.n_vertices();
  if (int(n0.size()) != nv) throw InputError("base normals: one surface normal per vertex is needed");
  if (!(opt.scale > 0) || !std::isfinite(opt.scale)) throw InputError("base normals: the scale must be positive");
  const double t = 0.5 * opt.scale * opt.scale;
  if (opt.progress) opt.progress(0, "Base normals: system");
  LaplacianOptions lo;
  lo.clamp_negative = true;
  LaplacianResult lap = surface.laplacian(lo);  // a copy: A is built in place below
  // A = M - t L. A vertex without area (isolated, or only in degenerate faces) has no coupling
  // either: its row becomes the identity times the median vertex area and it keeps its own normal.
  // (With 1 in place of a typical area, the 1,113 unreferenced vertices of the Stanford bunny
  // made up almost all of the right-hand side's norm, and a relative residual of 1e-3 left the
  // surface's base normals 6.6 deg (median), up to 122 deg, from the exact solve.)
  const double no_area_weight = typical_area(lap.mass);
  Eigen::SparseMatrix<double>& A = lap.L;
  A *= -t;
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const int* cols = A.innerIndexPtr() + A.outerIndexPtr()[v];
    const int len = A.outerIndexPtr()[v + 1] - A.outerIndexPtr()[v];
    double& d = A.valuePtr()[A.outerIndexPtr()[v] + (std::lower_bound(cols, cols + len, v) - cols)];
    if (lap.mass[v] > 0) {
      d += lap.mass[v];
    } else {
      d = no_area_weight;
    }
  }
  Eigen::MatrixXd B(nv, 3), X(nv, 3);
  for (int v = 0; v < nv; ++v) {
    const Vec3 n = n0[v].allFinite() ? n0[v] : Vec3(0, 0, 1);
    X.row(v) = n.transpose();
    B.row(v) = (lap.mass[v] > 0 ? lap.mass[v] : no_area_weight) * n.transpose();
  }
  BaseNormals out;
  out.expected_iterations = predicted_cg_iterations(A, lap.mass);
  SolverOptions so;
  so.method = opt.method;
  so.tolerance = opt.tolerance;
  so.max_iterations = opt.max_iterations;
  so.prefer_direct = out.expected_iterations > kMultilevelAboveIterations;
  so.progress = opt.progress;
  so.progress_from = 5;
  so.progress_to = 95;
  so.label = "Base normals: diffusion";
  out.solve = solve_spd(A, B, X, so);
  sized(out.normal, size_t(nv));
  for (int v = 0; v < nv; ++v) {
    const Vec3 x = X.row(v).transpose();
    const double l = x.norm();
    out.normal[v] = (l > 0 && std::isfinite(l)) ? Vec3(x / l) : (n0[v].allFinite() ? n0[v] : Vec3(0, 0, 1));
  }
  return out;
}

}  // namespace reliefkit
