// Benchmark of the scale space (reliefkit/multiscale/scale_space.h) against the explicit diffusion it
// replaces for large scales: a Gaussian bump on a plane of about N faces, smoothed to Gaussian
// scales of 2, 4, 8, 16 and 64 edge lengths; wall time of each, next to its accuracy (the bump's
// height against the exact Gaussian convolution).
//   build/bench/bench_scale_space [--sizes 1000000] [--repeat 1]
#include <omp.h>

#include <cmath>
#include <cstdio>

#include "bench_util.h"
#include "reliefkit/base/scale.h"
#include "reliefkit/multiscale/scale_space.h"
#include "reliefkit/base/smoothing.h"
#include "shapes.h"

using namespace reliefkit;

int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {1000000});
  std::printf("Scale space: implicit (4 steps per level) against explicit diffusion, %d threads\n",
              omp_get_max_threads());
  for (long target : args.sizes) {
    const int n = static_cast<int>(std::sqrt(target / 2.0));
    const double h = 2.0 / n, s0 = 20 * h, amp = 0.05 * s0;  // a bump 20 edge lengths wide
    auto bump = [&](double x, double y) { return amp * std::exp(-(x * x + y * y) / (2 * s0 * s0)); };
    const TriMesh m = rktest::height_field(bump, 1.0, n, 0.3, 3);
    int c = 0;
    for (int v = 0; v < m.n_vertices(); ++v)
      if (m.vertices[v].head<2>().norm() < m.vertices[c].head<2>().norm()) c = v;
    const std::vector<double> edges = {2, 4, 8, 16, 64};
    std::vector<double> sigmas;
    for (double e : edges) sigmas.push_back(e * h);
    auto truth = [&](double s) { return amp * s0 * s0 / (s0 * s0 + s * s); };
    std::printf("%zu faces, bump of %.0f edge lengths\n", m.faces.size(), s0 / h);
    std::printf("  %-28s %8s  %s\n", "", "time s", "bump height / Gaussian's at 2, 4, 8, 16, 64 edges");
    // Implicit: all levels in one pass.
    std::vector<double> height;
    const double t0 = rkbench::now();
    ScaleSpaceReport rep = scale_space(m, sigmas, {}, [&](int, const Surface& s) { height.push_back(s.mesh().vertices[c].z()); });
    const double t_implicit = rkbench::now() - t0;
    std::printf("  %-28s %8.2f  ", "implicit, all five levels", t_implicit);
    for (size_t k = 0; k < sigmas.size(); ++k) std::printf("%.4f ", height[k] / truth(sigmas[k]));
    std::printf("(%zu solves, %s)\n", rep.solves.size(), rep.converged ? "all converged" : "NOT converged");
    // Explicit: each level from the input, as pre-smoothing does it.
    const Surface surface = Surface::borrow(m);
    for (size_t k = 0; k < sigmas.size(); ++k) {
      std::vector<Vec3> x = m.vertices;
      const double t1 = rkbench::now();
      smooth_positions(surface, sigmas[k], x);
      const double t = rkbench::now() - t1;
      std::printf("  explicit, %2.0f edges (%5d steps) %8.2f  %.4f\n", edges[k], diffusion_steps(surface.scale(), sigmas[k]), t,
                  x[c].z() / truth(sigmas[k]));
    }
  }
}
