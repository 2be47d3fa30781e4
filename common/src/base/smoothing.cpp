#include "reliefkit/base/smoothing.h"

#include <algorithm>
#include <cmath>

#include "reliefkit/base/memory.h"

namespace reliefkit {

int diffusion_steps(const TriMesh& mesh, double scale) {
  if (!(scale > 0)) return 0;
  // The typical squared edge length: a median, so a few huge faces (a coarse plate, debris
  // beside the scan) do not cut the number of steps and leave the object unsmoothed.
  std::vector<double> l2;
  l2.reserve(mesh.faces.size() * 3);
  for (const auto& f : mesh.faces)
    for (int j = 0; j < 3; ++j) {
      double x = (mesh.vertices[f[j]] - mesh.vertices[f[(j + 1) % 3]]).squaredNorm();
      if (std::isfinite(x) && x > 0) l2.push_back(x);
    }
  if (l2.empty()) return 0;
  auto mid = l2.begin() + l2.size() / 2;
  std::nth_element(l2.begin(), mid, l2.end());
  // Mean squared edge over the edges at most 4x the median length: the mean is what one step
  // spreads by (it matches a Gaussian to 0.8 % on a grid), the trim keeps a coarse plate or debris
  // from cutting the number of steps.
  const double cap = 16 * *mid;
  double sum = 0;
  long long n = 0;
  for (double x : l2)
    if (x <= cap) sum += x, ++n;
  double per_step = 0.25 * sum / double(n);  // variance added per step, per direction
  double steps = std::ceil(scale * scale / per_step);
  if (std::isnan(steps)) return 0;
  return steps > 10000 ? 10000 : std::max(1, int(steps));
}

template <class T>
static void diffuse_impl(const TriMesh& mesh, const VertexRing& ring, double scale, std::vector<T>& x) {
  int steps = diffusion_steps(mesh, scale);
  const int nv = mesh.n_vertices();
  std::vector<T> y;
  sized(y, x.size(), x.empty() ? T() : x[0]);
  for (int s = 0; s < steps; ++s) {
#pragma omp parallel for schedule(static)
    for (int v = 0; v < nv; ++v) {
      int b = ring.offset[v], e = ring.offset[v + 1];
      if (b == e) {
        y[v] = x[v];
        continue;
      }
      T sum = x[ring.vertex[b]];
      for (int k = b + 1; k < e; ++k) sum += x[ring.vertex[k]];
      y[v] = 0.5 * x[v] + (0.5 / (e - b)) * sum;
    }
    x.swap(y);
  }
}

void diffuse(const TriMesh& mesh, const VertexRing& ring, double scale, std::vector<double>& values) {
  diffuse_impl(mesh, ring, scale, values);
}
void diffuse(const TriMesh& mesh, const VertexRing& ring, double scale, std::vector<Vec3>& values) {
  diffuse_impl(mesh, ring, scale, values);
}

void smooth_positions(const TriMesh& mesh, const MeshTopology& topology, double scale, std::vector<Vec3>& x) {
  const int steps = diffusion_steps(mesh, scale);
  if (steps == 0) return;
  const VertexRing& ring = topology.ring;
  const VertexRing& border = topology.border;
  const int nv = mesh.n_vertices();
  std::vector<Vec3> y;
  sized(y, x.size(), Vec3(Vec3::Zero()));
  for (int s = 0; s < steps; ++s) {
#pragma omp parallel for schedule(static)
    for (int v = 0; v < nv; ++v) {
      const bool on_border = border.offset[v + 1] - border.offset[v] == 2;
      const VertexRing& use = on_border ? border : ring;
      const int b = use.offset[v], e = use.offset[v + 1];
      if (b == e || (border.offset[v + 1] > border.offset[v] && !on_border)) {
        y[v] = x[v];  // isolated, or a non-manifold boundary vertex: kept in place
        continue;
      }
      Vec3 sum = x[use.vertex[b]];
      for (int k = b + 1; k < e; ++k) sum += x[use.vertex[k]];
      y[v] = 0.5 * x[v] + (0.5 / (e - b)) * sum;
    }
    x.swap(y);
  }
}

}  // namespace reliefkit
