#include "reliefkit/optimal_scale.h"

#include <algorithm>
#include <cmath>

#include "reliefkit/curvature.h"
#include "reliefkit/memory.h"
#include "reliefkit/scale.h"
#include "reliefkit/scale_selection.h"
#include "reliefkit/scale_space.h"

namespace reliefkit {

OptimalScale optimal_scale_ridges(const TriMesh& mesh, const OptimalScaleOptions& opt) {
  require_triangles(mesh);
  require_range(opt.min_scale_edges, "Smallest scale (edge lengths)", 0.1, 1000);
  require_range(opt.max_scale_edges, "Largest scale (edge lengths)", opt.min_scale_edges, 1000);
  require_range(opt.levels_per_octave, "Levels per octave", 1, 16);
  require_range(opt.gamma, "Scale normalisation gamma", 0.1, 1.45);  // a single peak needs gamma < 1.5
  const MeshTopology topology = mesh_topology(mesh);
  const double h = mesh_scale(mesh).edge;
  OptimalScale out;
  for (double e = opt.min_scale_edges; e <= opt.max_scale_edges * (1 + 1e-9);
       e *= std::pow(2.0, 1.0 / opt.levels_per_octave))
    out.levels.push_back(e * h);
  const int nl = static_cast<int>(out.levels.size()), nv = mesh.n_vertices();
  std::vector<double> f;  // vertex-major: f[v * nl + level]
  sized(f, size_t(nv) * size_t(nl));
  ScaleSpaceOptions so;
  so.topology = &topology;
  CurvatureOptions co;
  co.derivatives = false;
  co.topology = &topology;
  scale_space(mesh, out.levels, so, [&](int level, const TriMesh& smoothed) {
    if (opt.progress) opt.progress(100 * level / nl, "Optimal scale: scale space");
    const Curvature c = compute_curvature(smoothed, co);
#pragma omp parallel for schedule(static)
    for (int v = 0; v < nv; ++v) f[size_t(v) * nl + level] = std::max(std::abs(c.k1[v]), std::abs(c.k2[v]));
  });
  std::vector<double> t(nl);
  for (int k = 0; k < nl; ++k) t[k] = out.levels[k] * out.levels[k];
  sized(out.sigma, size_t(nv));
  sized(out.strength, size_t(nv));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const double* fv = f.data() + size_t(v) * nl;
    const double ts = select_scale(t, fv, 1, opt.gamma);
    out.sigma[v] = std::sqrt(ts);
    const int k = ts > 0 ? int(std::lower_bound(t.begin(), t.end(), ts) - t.begin()) : 0;
    out.strength[v] = ts > 0 ? std::pow(t[std::min(k, nl - 1)], opt.gamma) * fv[std::min(k, nl - 1)] : 0;
  }
  return out;
}

}  // namespace reliefkit
