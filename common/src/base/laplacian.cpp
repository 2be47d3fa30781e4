#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/work_counts.h"

#include <algorithm>
#include <cmath>

#include "reliefkit/base/curvature.h"
#include "reliefkit/base/memory.h"

namespace reliefkit {

LaplacianResult cotangent_laplacian(const TriMesh& mesh, const MeshTopology& topology, const LaplacianOptions& opt) {
  count_work(Work::Laplacian);
  const VertexFaces& vf = topology.faces;
  LaplacianResult r;
  const int nv = mesh.n_vertices();
  const long nf = static_cast<long>(mesh.faces.size());
  // Half cotangent of each corner's angle (the weight of the opposite edge); a degenerate face or
  // a sliver (kSliverAreaRatio) gets zeros everywhere.
  std::vector<std::array<double, 3>> half_cot;
  sized(half_cot, size_t(nf));
  long long degenerate = 0;
#pragma omp parallel for schedule(static) reduction(+ : degenerate)
  for (long i = 0; i < nf; ++i) {
    const auto& f = mesh.faces[i];
    std::array<double, 3> w{};
    bool ok = true;
    double longest = 0;  // the face's longest edge, squared (the sliver test's scale)
    for (int j = 0; j < 3; ++j)
      longest = std::max(longest, (mesh.vertices[f[(j + 1) % 3]] - mesh.vertices[f[j]]).squaredNorm());
    for (int j = 0; j < 3; ++j) {
      const Vec3 a = mesh.vertices[f[(j + 1) % 3]] - mesh.vertices[f[j]];
      const Vec3 b = mesh.vertices[f[(j + 2) % 3]] - mesh.vertices[f[j]];
      const double s = a.cross(b).norm();
      w[j] = 0.5 * a.dot(b) / s;
      if (!(s > kSliverAreaRatio * longest) || !std::isfinite(w[j])) ok = false;
      if (opt.clamp_negative && w[j] < 0) w[j] = 0;
    }
    if (!ok) {
      ++degenerate;
      w = {0, 0, 0};
    }
    half_cot[i] = w;
  }
  r.degenerate_faces = degenerate;

  // Row v: its ring and itself, sorted. The ring bounds the row's length, so the row is sized
  // first, then filled; entries are found by binary search (a fan's pole row stays linear).
  const VertexRing& ring = topology.ring;
  r.L.resize(nv, nv);
  r.L.resizeNonZeros(static_cast<Eigen::Index>(ring.vertex.size()) + nv);
  int* outer = r.L.outerIndexPtr();
  int* inner = r.L.innerIndexPtr();
  double* value = r.L.valuePtr();
  outer[0] = 0;
  for (int v = 0; v < nv; ++v) outer[v + 1] = ring.offset[v + 1] + v + 1;
#pragma omp parallel for schedule(dynamic, 4096)
  for (int v = 0; v < nv; ++v) {
    int* cols = inner + outer[v];
    double* vals = value + outer[v];
    const int len = outer[v + 1] - outer[v];
    std::copy(ring.vertex.begin() + ring.offset[v], ring.vertex.begin() + ring.offset[v + 1], cols);
    cols[len - 1] = v;
    std::sort(cols, cols + len);
    std::fill(vals, vals + len, 0.0);
    auto add = [&](int u, double w) { vals[std::lower_bound(cols, cols + len, u) - cols] += w; };
    double sum = 0;
    for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
      const auto& f = mesh.faces[vf.face[k]];
      const auto& w = half_cot[vf.face[k]];
      const int c = vf.corner[k];
      // Edge (v, f[c+1]) is opposite corner c+2, edge (v, f[c+2]) opposite corner c+1.
      const int u1 = f[(c + 1) % 3], u2 = f[(c + 2) % 3];
      const double w1 = w[(c + 2) % 3], w2 = w[(c + 1) % 3];
      if (u1 != v) add(u1, w1), sum += w1;
      if (u2 != v) add(u2, w2), sum += w2;
    }
    add(v, -sum);
  }

  auto ca = corner_areas(mesh);
  r.mass = Eigen::VectorXd::Zero(nv);
  for (long i = 0; i < nf; ++i)
    for (int j = 0; j < 3; ++j) r.mass[mesh.faces[i][j]] += ca[i][j];
  r.M.resize(nv, nv);
  r.M.reserve(Eigen::VectorXi::Constant(nv, 1));
  for (int v = 0; v < nv; ++v) r.M.insert(v, v) = r.mass[v];
  r.M.makeCompressed();
  return r;
}

LaplacianResult cotangent_laplacian(const TriMesh& mesh, const LaplacianOptions& options) {
  MeshTopology t;
  t.faces = vertex_faces(mesh);
  t.ring = vertex_rings(mesh, t.faces);
  return cotangent_laplacian(mesh, t, options);
}

Eigen::SparseMatrix<double> uniform_laplacian(const VertexRing& ring) {
  count_work(Work::Laplacian);
  const int n = int(ring.offset.size()) - 1;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(ring.vertex.size() + size_t(n));
  for (int i = 0; i < n; ++i) {
    const int degree = ring.offset[i + 1] - ring.offset[i];
    if (degree == 0) continue;
    entries.emplace_back(i, i, 1.0);
    for (int k = ring.offset[i]; k < ring.offset[i + 1]; ++k) entries.emplace_back(i, ring.vertex[k], -1.0 / degree);
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

}  // namespace reliefkit
