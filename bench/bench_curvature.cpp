// Benchmark of the curvature module: wall time and peak memory of curvature + derivative tensor
// on jittered tori (R = 3, r = 1) of ~100 K, 1 M and 4 M faces, for both estimators, with the
// accuracy of what was timed (median error of k1 and k2 against the exact values, in % of the
// largest curvature 1/r), so that a fast failure cannot pass as a speed-up.
//   build/bench/bench_curvature [--sizes 100000,1000000,4000000] [--repeat 3]
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "reliefkit/base/curvature.h"
#include "bench_util.h"
#include "shapes.h"

using namespace reliefkit;


int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {100000, 1000000, 4000000});
  const int repeat = args.repeat;
  std::printf("ReliefKit curvature benchmark: %d threads (OpenMP), best of %d runs\n", omp_get_max_threads(), repeat);
  std::printf("%-10s %-10s %-28s %9s %12s %10s %16s\n", "faces", "vertices", "computation", "time s", "s / M faces",
              "peak MiB", "k1 / k2 error %");
  for (long target : args.sizes) {
    const int nv = std::max(8, int(std::sqrt(target / 5.0))), nu = std::max(8, int(target / 2 / nv));
    const double R = 3, r = 1;
    TriMesh m = rktest::torus(R, r, nu, nv, 0.3, 1);
    struct Config {
      const char* name;
      CurvatureEstimator est;
      bool deriv;
    } configs[] = {{"jet: curvature + derivs", CurvatureEstimator::Jet, true},
                   {"face fit: curvature + derivs", CurvatureEstimator::FaceFit, true},
                   {"face fit: curvature only", CurvatureEstimator::FaceFit, false}};
    for (const auto& c : configs) {
      double best = 1e30;
      double peak = 0;
      Curvature k;
      for (int run = 0; run < repeat; ++run) {
        rkbench::PeakMemory mem;
        mem.start();
        CurvatureOptions opt;
        opt.estimator = c.est;
        opt.derivatives = c.deriv;
        double t0 = rkbench::now();
        k = compute_curvature(m, opt);
        double t = rkbench::now() - t0;
        best = std::min(best, t);
        peak = std::max(peak, mem.grown_mib());
        if (k.k1.empty()) return 1;
      }
      std::vector<double> e1, e2;
      for (int i = 0; i < m.n_vertices(); ++i) {
        double u, v;
        rktest::torus_params(R, r, m.vertices[i], u, v);
        e1.push_back(std::abs(k.k1[i] - 1 / r) * r);
        e2.push_back(std::abs(k.k2[i] - std::cos(v) / (R + r * std::cos(v))) * r);
      }
      std::printf("%-10d %-10d %-28s %9.3f %12.3f %10.1f %7.3f / %6.3f\n", m.n_faces(), m.n_vertices(), c.name, best,
                  best / (m.n_faces() / 1e6), peak, 100 * rktest::median(e1), 100 * rktest::median(e2));
    }
  }
  return 0;
}
