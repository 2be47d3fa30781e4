// Benchmark of the whole demarcating-curves computation (pre-smoothing, curvature and
// derivatives, curvature gradient, zero-crossing extraction, threshold, short-curve removal)
// with the defaults the filter uses, on the cylinder relief of ~1 M and ~4 M faces (a raised and
// a sunken disc), clean and with 10 % noise; recall / precision of what was timed against the
// relief's true outline (within one edge length), so a fast failure cannot pass as a speed-up.
//   build/bench/bench_demarcating [--sizes 1000000,4000000] [--repeat 3]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "reliefkit/demarcating/demarcating.h"
#include "bench_util.h"
#include "reliefs.h"
#include "shapes.h"

using namespace reliefkit;


int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {1000000, 4000000});
  const int repeat = args.repeat;
  std::printf("ReliefKit demarcating-curves benchmark: %d threads, best of %d runs, filter defaults\n",
              omp_get_max_threads(), repeat);
  for (long target : args.sizes)
    for (double noise : {0.0, 0.1}) {
    rktest::ReliefShape shape;
    shape.noise = noise;
    const rktest::Relief relief = rktest::discs_on_cylinder_of_size(target, shape);
    const TriMesh& m = relief.mesh;
    rktest::Detection d{0, 0};
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
      d = rktest::score(relief, res.curves, relief.mean_edge);
    }
    std::printf("\n%d faces, %d vertices, noise %.0f %%: %.3f s (%.3f s per M faces), peak +%.0f MiB, %zu curve "
                "segments, recall %.3f precision %.3f\n",
                m.n_faces(), m.n_vertices(), 100 * noise, best, best / (m.n_faces() / 1e6), peak, segments, d.recall,
                d.precision);
    for (const auto& kv : best_stages)
      if (!kv.first.empty()) std::printf("  %-28s %.3f s\n", kv.first.c_str(), kv.second);
    }
  return 0;
}
