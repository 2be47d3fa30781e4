#include "reliefkit/base/smoothing.h"

#include <algorithm>
#include <cmath>

#include "reliefkit/base/memory.h"

namespace reliefkit {

int diffusion_steps(const MeshScale& scale, double sigma) {
  if (!(sigma > 0) || !(scale.step_variance > 0)) return 0;
  const double steps = std::ceil(sigma * sigma / scale.step_variance);
  if (std::isnan(steps)) return 0;
  return steps > 10000 ? 10000 : std::max(1, int(steps));
}

template <class T>
static void diffuse_impl(const Surface& surface, double sigma, std::vector<T>& x) {
  const int steps = diffusion_steps(surface.scale(), sigma);
  if (steps == 0) return;
  const VertexRing& ring = surface.topology().ring;
  const int nv = surface.n_vertices();
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

void diffuse(const Surface& surface, double sigma, std::vector<double>& values) {
  diffuse_impl(surface, sigma, values);
}
void diffuse(const Surface& surface, double sigma, std::vector<Vec3>& values) {
  diffuse_impl(surface, sigma, values);
}

void smooth_positions(const Surface& surface, double sigma, std::vector<Vec3>& x) {
  const int steps = diffusion_steps(surface.scale(), sigma);
  if (steps == 0) return;
  const VertexRing& ring = surface.topology().ring;
  const VertexRing& border = surface.topology().border;
  const int nv = surface.n_vertices();
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

Surface smoothed_surface(const Surface& surface, double sigma) {
  if (!(sigma > 0)) return surface;
  std::vector<Vec3> x;
  const std::vector<Vec3>& input = surface.mesh().vertices;
  sized(x, input.size(), Vec3(Vec3::Zero()));
  std::copy(input.begin(), input.end(), x.begin());
  smooth_positions(surface, sigma, x);
  return surface.with_positions(std::move(x));
}

}  // namespace reliefkit
