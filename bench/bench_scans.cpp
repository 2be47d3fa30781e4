// The curve filters at their defaults on the real scans of ../shared/data (and the bundled coin):
// time, curve length, and how continuous the curves are — the share of the curve length in
// pieces shorter than 10 edge lengths (dashes) — with the noise and pre-smoothing chosen.
//   build/bench/bench_scans [scan.ply|scan.obj ...]
#include <omp.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bench_util.h"
#include "reliefkit/demarcating/demarcating.h"
#include "mesh_files.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/relief_edges/ridges.h"

using namespace reliefkit;

namespace {

struct Continuity {
  size_t chains = 0;
  double length = 0, short_share = 0;  // share of the length in chains shorter than 10 edges
};

Continuity continuity(const Polylines& p, double edge) {
  Continuity c;
  double short_len = 0;
  for (const auto& ch : p.chains()) {
    double l = 0;
    for (size_t i = 1; i < ch.size(); ++i) l += (p.points[ch[i]] - p.points[ch[i - 1]]).norm();
    ++c.chains;
    c.length += l;
    if (l < 10 * edge) short_len += l;
  }
  c.short_share = c.length > 0 ? short_len / c.length : 0;
  return c;
}

void row(const char* scan, const char* filter, double secs, const Polylines& p, const ScaledCurvature& s,
         const std::string& extra = "") {
  Continuity c = continuity(p, s.scale.edge);
  std::printf("%-22s %-20s %7.2f %8zu %8zu %10.0f %8.3f %7.1f%% %6.2f  %s\n", scan, filter, secs, p.segments.size(),
              c.chains, c.length / s.scale.edge, c.short_share, 100 * s.noise.relative,
              s.presmoothing / s.scale.edge, extra.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scans;
  for (int i = 1; i < argc; ++i) scans.push_back(argv[i]);
  if (scans.empty()) {
    scans.push_back(std::string(RELIEFKIT_SOURCE_DIR) + "/examples/data/penny.ply");
    for (const char* n : {"fertility.obj", "stanford-bunny.obj"})
      scans.push_back(std::string(RELIEFKIT_SOURCE_DIR) + "/../shared/data/meshes/" + n);
  }
  std::printf("Curve filters at defaults on real scans, %d threads\n", omp_get_max_threads());
  std::printf("%-22s %-20s %7s %8s %8s %10s %8s %8s %6s\n", "scan", "filter", "time s", "segments", "pieces",
              "length/e", "<10e", "noise", "smooth");
  for (const auto& path : scans) {
    TriMesh m;
    if (!rkbench::read_scan(path, m)) continue;
    const std::string name = path.substr(path.find_last_of('/') + 1);
    double t0 = rkbench::now();
    DemarcatingResult d = compute_demarcating(m);
    row(name.c_str(), "demarcating", rkbench::now() - t0, d.curves, d);
    t0 = rkbench::now();
    ReliefEdgeResult r = compute_relief_edges(m);
    char extra[128];
    std::snprintf(extra, sizeof extra, "strong tilt %.1f deg (crossings %.1f, noise %.1f)", r.strong_angle * 57.29578,
                  r.automatic_angle * 57.29578, r.noise_angle * 57.29578);
    row(name.c_str(), "relief edges", rkbench::now() - t0, r.edges, r, extra);
    t0 = rkbench::now();
    RidgeValleyResult rv = compute_ridges_valleys(m);
    const double t = rkbench::now() - t0;
    row(name.c_str(), "ridges", t, rv.ridges, rv);
    row(name.c_str(), "valleys", t, rv.valleys, rv);
  }
  return 0;
}
