// How the curve filters' cores grow with the mesh (issue 40, point 3): Demarcating Curves, Relief
// Edges and Multi-scale Relief Edges at their defaults on the cylinder relief with a raised and a
// sunken disc (clean, or with --noise in mean edge lengths), at about 1, 4 and 10 M faces, one after the other in this process. For each:
// the wall time, the time per million faces and its ratio to the smallest size's (1.0 = linear),
// the peak resident memory above what the process held before the call (bytes per face; the mesh
// itself is held before), and recall / precision of the curves against the discs' outlines (within
// two edge lengths, as issue 40 counts kept length), so that a fast failure cannot pass as a speed-up. The slowest stages (by the
// filters' progress reports) show where the growth is.
//   build/bench/bench_sizes [--sizes 1000000,4000000,10000000] [--repeat 1] [--noise 0]
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bench_util.h"
#include "reliefkit/demarcating/demarcating.h"
#include "reliefkit/multiscale/multiscale.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefs.h"

using namespace reliefkit;

namespace {

struct Measured {
  double seconds = 1e30, bytes_per_face = 0;
  rktest::Detection detection{0, 0};
  std::map<std::string, double> stages;
};

using CurveFilter = std::function<Polylines(const Surface&)>;

Measured measure(const rktest::Relief& relief, const CurveFilter& filter, int repeat) {
  Measured m;
  for (int r = 0; r < repeat; ++r) {
    rkbench::PeakMemory mem;
    mem.start();
    rkbench::g_stages.start();
    const double t0 = rkbench::now();
    const Polylines curves = filter(Surface::borrow(relief.mesh));
    const double t = rkbench::now() - t0;
    rkbench::stage_progress(100, "");
    m.bytes_per_face = std::max(m.bytes_per_face, mem.grown_mib() * 1048576.0 / relief.mesh.n_faces());
    if (t < m.seconds) m.seconds = t, m.stages = rkbench::g_stages.time;
    m.detection = rktest::score(relief, curves, 2 * relief.mean_edge);
  }
  return m;
}

void print_slowest_stages(const std::map<std::string, double>& stages, double total) {
  std::vector<std::pair<double, std::string>> by_time;
  for (const auto& [name, t] : stages)
    if (!name.empty()) by_time.push_back({t, name});
  std::sort(by_time.rbegin(), by_time.rend());
  std::printf("      slowest stages:");
  for (size_t i = 0; i < by_time.size() && i < 3; ++i)
    std::printf(" %s %.2f s (%.0f %%);", by_time[i].second.c_str(), by_time[i].first, 100 * by_time[i].first / total);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {1000000, 4000000, 10000000});  // --noise is read below
  const int repeat = args.repeat;
  rktest::ReliefShape shape;
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], "--noise")) shape.noise = std::atof(argv[i + 1]);
  const std::vector<std::pair<std::string, CurveFilter>> filters = {
      {"Demarcating Curves",
       [](const Surface& s) {
         DemarcatingParams p;
         p.progress = rkbench::stage_progress;
         return compute_demarcating(s, p).curves;
       }},
      {"Relief Edges",
       [](const Surface& s) {
         ReliefEdgeParams p;
         p.progress = rkbench::stage_progress;
         return compute_relief_edges(s, p).edges;
       }},
      {"Multi-scale Relief Edges",
       [](const Surface& s) {
         OptimalScaleOptions o;
         o.progress = rkbench::stage_progress;
         return multiscale_relief_edges(s, o, {}).curves.edges;
       }},
  };
  std::printf("ReliefKit curve filters by mesh size: %d threads, best of %d run(s), filter defaults, disc cylinder "
              "relief, noise %.2f edge lengths\n",
              omp_get_max_threads(), repeat, shape.noise);
  std::printf("%-26s %10s %9s %9s %12s %10s %7s %9s\n", "filter", "faces", "s", "s / M", "vs smallest", "B / face",
              "recall", "precision");
  std::map<std::string, double> first_per_million;
  for (long target : args.sizes) {
    const rktest::Relief relief = rktest::discs_on_cylinder_of_size(target, shape);
    const double millions = relief.mesh.n_faces() / 1e6;
    for (const auto& [name, filter] : filters) {
      const Measured m = measure(relief, filter, repeat);
      const double per_million = m.seconds / millions;
      if (!first_per_million.count(name)) first_per_million[name] = per_million;
      std::printf("%-26s %10d %9.2f %9.2f %12.2f %10.0f %7.3f %9.3f\n", name.c_str(), relief.mesh.n_faces(), m.seconds,
                  per_million, per_million / first_per_million[name], m.bytes_per_face, m.detection.recall,
                  m.detection.precision);
      print_slowest_stages(m.stages, m.seconds);
      std::fflush(stdout);
    }
  }
  return 0;
}
