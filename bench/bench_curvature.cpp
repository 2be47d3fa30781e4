// Benchmark of the curvature module: wall time and peak memory of curvature + derivative tensor
// on synthetic meshes of ~100 K, 1 M and 4 M faces (a jittered torus carrying a relief), for
// both estimators and per stage. Prints a table; figures go into docs/benchmarks.md.
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

#include "reliefkit/curvature.h"
#include "bench_util.h"
#include "shapes.h"

using namespace reliefkit;


int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {100000, 1000000, 4000000});
  const int repeat = args.repeat;
  std::printf("ReliefKit curvature benchmark: %d threads (OpenMP), best of %d runs\n", omp_get_max_threads(), repeat);
  std::printf("%-10s %-10s %-28s %9s %12s %10s\n", "faces", "vertices", "computation", "time s", "s / M faces",
              "peak MiB");
  for (long target : args.sizes) {
    TriMesh m = rktest::relief_torus(target);
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
      for (int r = 0; r < repeat; ++r) {
        rkbench::PeakMemory mem;
        mem.start();
        CurvatureOptions opt;
        opt.estimator = c.est;
        opt.derivatives = c.deriv;
        double t0 = rkbench::now();
        Curvature k = compute_curvature(m, opt);
        double t = rkbench::now() - t0;
        best = std::min(best, t);
        peak = std::max(peak, mem.grown_mib());
        if (k.k1.empty()) return 1;
      }
      std::printf("%-10d %-10d %-28s %9.3f %12.3f %10.1f\n", m.n_faces(), m.n_vertices(), c.name, best,
                  best / (m.n_faces() / 1e6), peak);
    }
  }
  return 0;
}
