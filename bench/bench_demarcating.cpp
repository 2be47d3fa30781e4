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
std::map<std::string, double> stage_time;
std::string stage;
double stage_start = 0;
bool progress(int, const char* what) {
  double t = now();
  if (!stage.empty()) stage_time[stage] += t - stage_start;
  stage = what;
  stage_start = t;
  return true;
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes = {1000000, 4000000};
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
  std::printf("ReliefKit demarcating-curves benchmark: %d threads, best of %d runs, filter defaults\n",
              omp_get_max_threads(), repeat);
  for (long target : sizes) {
    TriMesh m = rktest::relief_torus(target);
    double best = 1e30;
    long peak = 0;
    size_t segments = 0;
    std::map<std::string, double> best_stages;
    for (int r = 0; r < repeat; ++r) {
      long base = status_kb("VmRSS:");
      std::ofstream("/proc/self/clear_refs") << "5";
      stage_time.clear();
      stage.clear();
      DemarcatingParams p;
      p.progress = progress;
      double t0 = now();
      stage_start = t0;
      DemarcatingResult res = compute_demarcating(m, p);
      double t = now() - t0;
      progress(100, "");
      if (t < best) best = t, best_stages = stage_time;
      peak = std::max(peak, status_kb("VmHWM:") - base);
      segments = res.curves.segments.size();
    }
    std::printf("\n%d faces, %d vertices: %.3f s (%.3f s per M faces), peak +%.0f MiB, %zu curve segments\n",
                m.n_faces(), m.n_vertices(), best, best / (m.n_faces() / 1e6), peak / 1024.0, segments);
    for (const auto& kv : best_stages)
      if (!kv.first.empty()) std::printf("  %-28s %.3f s\n", kv.first.c_str(), kv.second);
  }
  return 0;
}
