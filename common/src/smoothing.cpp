#include "reliefkit/smoothing.h"

#include <cmath>

#include "reliefkit/memory.h"

namespace reliefkit {

int diffusion_steps(const TriMesh& mesh, double scale) {
  if (!(scale > 0)) return 0;
  double sum2 = 0;
  long long n = 0;
  for (const auto& f : mesh.faces)
    for (int j = 0; j < 3; ++j) {
      double l2 = (mesh.vertices[f[j]] - mesh.vertices[f[(j + 1) % 3]]).squaredNorm();
      if (std::isfinite(l2)) {
        sum2 += l2;
        ++n;
      }
    }
  if (n == 0 || !(sum2 > 0)) return 0;
  double per_step = 0.25 * sum2 / n;  // variance added per step, per direction
  double steps = std::ceil(scale * scale / per_step);
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

}  // namespace reliefkit
