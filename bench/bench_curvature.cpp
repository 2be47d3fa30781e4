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
#include "shapes.h"

using namespace reliefkit;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

long status_kb(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key, 0) == 0) return std::stol(line.substr(std::strlen(key)));
  return -1;
}
void reset_peak() { std::ofstream("/proc/self/clear_refs") << "5"; }

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes = {100000, 1000000, 4000000};
  int repeat = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--sizes")) {
      sizes.clear();
      std::stringstream ss(argv[i + 1]);
      std::string tok;
      while (std::getline(ss, tok, ',')) sizes.push_back(std::stol(tok));
    } else if (!std::strcmp(argv[i], "--repeat")) {
      repeat = std::atoi(argv[i + 1]);
    }
  }
  std::printf("ReliefKit curvature benchmark: %d threads (OpenMP), best of %d runs\n", omp_get_max_threads(), repeat);
  std::printf("%-10s %-10s %-28s %9s %12s %10s\n", "faces", "vertices", "computation", "time s", "s / M faces",
              "peak MiB");
  for (long target : sizes) {
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
      long peak = 0;
      for (int r = 0; r < repeat; ++r) {
        long base = status_kb("VmRSS:");
        reset_peak();
        CurvatureOptions opt;
        opt.estimator = c.est;
        opt.derivatives = c.deriv;
        double t0 = now();
        Curvature k = compute_curvature(m, opt);
        double t = now() - t0;
        best = std::min(best, t);
        peak = std::max(peak, status_kb("VmHWM:") - base);
        if (k.k1.empty()) return 1;
      }
      std::printf("%-10d %-10d %-28s %9.3f %12.3f %10.1f\n", m.n_faces(), m.n_vertices(), c.name, best,
                  best / (m.n_faces() / 1e6), peak / 1024.0);
    }
  }
  return 0;
}
