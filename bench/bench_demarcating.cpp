// Benchmark of the whole demarcating-curves computation (pre-smoothing, curvature and
// derivatives, curvature gradient, zero-crossing extraction, threshold, short-curve removal)
// on synthetic relief tori of ~1 M and ~4 M faces, with the defaults the filter uses.
//   build/bench/bench_demarcating [--sizes 1000000,4000000] [--repeat 3]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "demarcating.h"
#include "bench_util.h"
#include "shapes.h"

using namespace reliefkit;


int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {1000000, 4000000});
  const int repeat = args.repeat;
  std::printf("ReliefKit demarcating-curves benchmark: %d threads, best of %d runs, filter defaults\n",
              omp_get_max_threads(), repeat);
  for (long target : args.sizes) {
    TriMesh m = rktest::relief_torus(target);
    double best = 1e30;
    double peak = 0;
    size_t segments = 0;
    std::map<std::string, double> best_stages;
    for (int r = 0; r < repeat; ++r) {
      rkbench::PeakMemory mem;
      mem.start();
      rkbench::g_stages.start();
      DemarcatingParams p;
      p.progress = rkbench::stage_progress;
      double t0 = rkbench::now();
            DemarcatingResult res = compute_demarcating(m, p);
      double t = rkbench::now() - t0;
      rkbench::stage_progress(100, "");
      if (t < best) best = t, best_stages = rkbench::g_stages.time;
      peak = std::max(peak, mem.grown_mib());
      segments = res.curves.segments.size();
    }
    std::printf("\n%d faces, %d vertices: %.3f s (%.3f s per M faces), peak +%.0f MiB, %zu curve segments\n",
                m.n_faces(), m.n_vertices(), best, best / (m.n_faces() / 1e6), peak, segments);
    for (const auto& kv : best_stages)
      if (!kv.first.empty()) std::printf("  %-28s %.3f s\n", kv.first.c_str(), kv.second);
  }
  return 0;
}
