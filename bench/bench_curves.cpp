// Benchmark of the three curve filters' cores in one run, on the same synthetic relief (a raised
// and a sunken disc on a cylinder with 10 % normal noise):
// Demarcating Curves, Relief Edges (including base normals) and Ridges and Valleys, with the
// filters' defaults; wall time, peak memory, and the relief-edge stages.
//   build/bench/bench_curves [--sizes 1000000] [--repeat 3]
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>

#include "reliefkit/demarcating/demarcating.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/relief_edges/ridges.h"
#include "reliefs.h"
#include "bench_util.h"
#include "shapes.h"

using namespace reliefkit;


int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {1000000});
  const int repeat = args.repeat;
  std::printf("ReliefKit curve filters (cores, defaults), %d threads, best of %d runs\n", omp_get_max_threads(), repeat);
  std::printf("%-10s %-32s %9s %12s %10s %10s %s\n", "faces", "filter core", "time s", "s / M faces", "peak MiB",
              "segments", "recall / precision (within half the step width)");
  for (long target : args.sizes) {
    // A raised and a sunken disc on a cylinder, 10 % normal noise, about `target` faces.
    rktest::ReliefShape shape;
    shape.noise = 0.1;
    const rktest::Relief relief = rktest::discs_on_cylinder_of_size(target, shape);
    const TriMesh& m = relief.mesh;
    // Each run returns its curves; they are scored against the relief's true outline, so a fast
    // failure cannot pass as a speed-up. (Ridges and valleys are not outlines: not scored.)
    std::map<std::string, double> relief_stages;
    const std::pair<const char*, std::function<Polylines()>> runs[] = {
        {"Demarcating Curves",
         [&] {
           DemarcatingParams p;
           return compute_demarcating(m, p).curves;
         }},
        {"Relief Edges (with base normals)",
         [&] {
           ReliefEdgeParams p;
           p.progress = rkbench::stage_progress;
           return compute_relief_edges(m, p).edges;
         }},
        {"Ridges and Valleys",
         [&] {
           RidgeValleyResult r = compute_ridges_valleys(m);
           Polylines both = r.ridges;  // segments counted: ridges and valleys
           const int off = static_cast<int>(both.points.size());
           both.points.insert(both.points.end(), r.valleys.points.begin(), r.valleys.points.end());
           both.strength.insert(both.strength.end(), r.valleys.strength.begin(), r.valleys.strength.end());
           for (const auto& sg : r.valleys.segments) both.segments.push_back({sg[0] + off, sg[1] + off});
           return both;
         }}};
    for (const auto& [name, fn] : runs) {
      double best = 1e30;
      double peak = 0;
      size_t segs = 0;
      rktest::Detection d{0, 0};
      for (int r = 0; r < repeat; ++r) {
        rkbench::PeakMemory mem;
        mem.start();
        rkbench::g_stages.start();
        double t0 = rkbench::now();
        Polylines curves = fn();
        double t = rkbench::now() - t0;  // the scoring below is not timed
        segs = curves.segments.size();
        // Scored within half the step's width in object space, the same at every resolution.
        if (std::string(name) != "Ridges and Valleys") d = rktest::score(relief, curves, 0.5 * shape.width);
        rkbench::stage_progress(100, "");
        if (t < best) {
          best = t;
          if (!rkbench::g_stages.time.empty()) relief_stages = rkbench::g_stages.time;
        }
        peak = std::max(peak, mem.grown_mib());
      }
      const bool scored = std::string(name) != "Ridges and Valleys";
      std::printf("%-10d %-32s %9.3f %12.3f %10.0f %10zu %s\n", m.n_faces(), name, best, best / (m.n_faces() / 1e6),
                  peak, segs, scored ? (std::to_string(d.recall).substr(0, 5) + " / " + std::to_string(d.precision).substr(0, 5)).c_str() : "-");
    }
    std::printf("  relief-edge stages (best run):\n");
    for (const auto& kv : relief_stages)
      if (!kv.first.empty()) std::printf("    %-26s %.3f s\n", kv.first.c_str(), kv.second);
  }
  return 0;
}
