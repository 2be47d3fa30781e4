// ReliefKit — coarse copies of meshes. See coarsening.h.
#include "reliefkit/base/coarsening.h"

#include <Eigen/Sparse>
#include <algorithm>

#include "reliefkit/base/multilevel.h"

namespace reliefkit {
namespace {

// The mesh's edge graph as a symmetric matrix (what aggregate_vertices reads).
Eigen::SparseMatrix<double> edge_graph(const TriMesh& mesh) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(6 * mesh.faces.size());
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      entries.emplace_back(f[k], f[(k + 1) % 3], -1.0);
      entries.emplace_back(f[(k + 1) % 3], f[k], -1.0);
    }
  Eigen::SparseMatrix<double> A(mesh.n_vertices(), mesh.n_vertices());
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// The faces of `mesh` renumbered by `to` that join three distinct vertices, each once (the first
// one's orientation kept).
std::vector<std::array<int, 3>> joining_faces(const TriMesh& mesh, const std::vector<int>& to) {
  std::vector<std::pair<std::array<int, 3>, std::array<int, 3>>> keyed;  // (sorted corners, face)
  keyed.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    const std::array<int, 3> g{to[size_t(f[0])], to[size_t(f[1])], to[size_t(f[2])]};
    if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) continue;
    std::array<int, 3> key = g;
    std::sort(key.begin(), key.end());
    keyed.push_back({key, g});
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::array<int, 3>> faces;
  for (size_t k = 0; k < keyed.size(); ++k)
    if (k == 0 || keyed[k].first != keyed[k - 1].first) faces.push_back(keyed[k].second);
  return faces;
}

// One level: the mesh's vertices aggregated, each aggregate at its members' mean.
CoarseMesh aggregated(const TriMesh& mesh) {
  CoarseMesh c;
  int count = 0;
  c.vertex_of = aggregate_vertices(edge_graph(mesh), count);
  c.mesh.vertices.assign(size_t(count), Vec3::Zero());
  std::vector<int> members(size_t(count), 0);
  for (int i = 0; i < mesh.n_vertices(); ++i) {
    c.mesh.vertices[size_t(c.vertex_of[size_t(i)])] += mesh.vertices[size_t(i)];
    ++members[size_t(c.vertex_of[size_t(i)])];
  }
  for (int a = 0; a < count; ++a) c.mesh.vertices[size_t(a)] /= std::max(members[size_t(a)], 1);
  c.mesh.faces = joining_faces(mesh, c.vertex_of);
  return c;
}
// Points in a grid of cubic cells of side at least `reach` (at most 128 cells a side): the points
// within `reach` of a position are in the 27 cells around it.
class PointCells {
 public:
  PointCells(const std::vector<Vec3>& points, double reach) {
    lo_ = Vec3::Constant(1e300);
    Vec3 hi = Vec3::Constant(-1e300);
    for (const auto& p : points) lo_ = lo_.cwiseMin(p), hi = hi.cwiseMax(p);
    cell_ = std::max(reach, (hi - lo_).maxCoeff() / 128);
    for (int k = 0; k < 3; ++k) dims_[k] = points.empty() ? 1 : int((hi[k] - lo_[k]) / cell_) + 1;
    start_.assign(size_t(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    for (const auto& p : points) ++start_[index(cell_of(p)) + 1];
    for (size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    point_.resize(points.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (size_t k = 0; k < points.size(); ++k) point_[size_t(fill[index(cell_of(points[k]))]++)] = int(k);
  }
  template <class F>
  void for_each_near(const Vec3& p, F&& visit) const {
    const Eigen::Vector3i c = cell_of(p);
    for (int x = std::max(c.x() - 1, 0); x <= std::min(c.x() + 1, dims_[0] - 1); ++x)
      for (int y = std::max(c.y() - 1, 0); y <= std::min(c.y() + 1, dims_[1] - 1); ++y)
        for (int z = std::max(c.z() - 1, 0); z <= std::min(c.z() + 1, dims_[2] - 1); ++z) {
          const size_t k = index({x, y, z});
          for (int j = start_[k]; j < start_[k + 1]; ++j) visit(point_[size_t(j)]);
        }
  }

 private:
  // The cell of p, clamped one cell outside the grid at most (so a far point finds nothing).
  Eigen::Vector3i cell_of(const Vec3& p) const {
    Eigen::Vector3i c;
    for (int k = 0; k < 3; ++k) c[k] = int(std::clamp(std::floor((p[k] - lo_[k]) / cell_), -2.0, double(dims_[k]) + 1));
    return c;
  }
  size_t index(const Eigen::Vector3i& c) const { return (size_t(c.x()) * dims_[1] + size_t(c.y())) * dims_[2] + size_t(c.z()); }
  Vec3 lo_;
  double cell_ = 1;
  int dims_[3] = {1, 1, 1};
  std::vector<int> start_;  // per cell, its first point in point_
  std::vector<int> point_;
};
}  // namespace

CoarseMesh coarsen_mesh(const TriMesh& fine, int most_faces) {
  CoarseMesh out;
  out.mesh = fine;
  out.vertex_of.resize(size_t(fine.n_vertices()));
  for (int i = 0; i < fine.n_vertices(); ++i) out.vertex_of[size_t(i)] = i;
  while (out.mesh.n_faces() > most_faces) {
    CoarseMesh next = aggregated(out.mesh);
    if (2 * next.mesh.n_vertices() > out.mesh.n_vertices()) break;  // no longer shrinking
    for (int& v : out.vertex_of) v = next.vertex_of[size_t(v)];
    out.mesh = std::move(next.mesh);
  }
  return out;
}

Interpolation interpolation_from_coarse(const TriMesh& fine, const CoarseMesh& coarse) {
  const double r = 1.5 * edge_length_stats(coarse.mesh).mean, r2 = r * r;
  // Only the coarse surface carries: a coarse vertex in no face (an unreferenced vertex of the
  // fine mesh is an aggregate of its own) would be a free value nothing else holds.
  std::vector<char> on_surface(coarse.mesh.vertices.size(), 0);
  for (const auto& f : coarse.mesh.faces)
    for (int v : f) on_surface[size_t(v)] = 1;
  const PointCells cells(coarse.mesh.vertices, r);
  const int n = fine.n_vertices();
  std::vector<std::vector<std::pair<int, double>>> rows(static_cast<size_t>(n));
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(n); ++i) {
    const Vec3& p = fine.vertices[size_t(i)];
    auto& row = rows[size_t(i)];
    double total = 0;
    cells.for_each_near(p, [&](int c) {
      if (!on_surface[size_t(c)]) return;
      const double t = 1 - (coarse.mesh.vertices[size_t(c)] - p).squaredNorm() / r2;
      if (t > 0) row.push_back({c, t * t}), total += t * t;
    });
    if (total == 0) row = {{coarse.vertex_of[size_t(i)], 1.0}}, total = 1;
    for (auto& [c, w] : row) w /= total;
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i)
    for (const auto& [c, w] : rows[size_t(i)]) entries.emplace_back(i, c, w);
  Interpolation P(n, coarse.mesh.n_vertices());
  P.setFromTriplets(entries.begin(), entries.end());
  return P;
}

}  // namespace reliefkit
