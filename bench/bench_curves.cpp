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

#include "demarcating.h"
#include "relief_edges.h"
#include "ridges.h"
#include "reliefs.h"
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
  std::vector<long> sizes = {1000000};
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
  std::printf("ReliefKit curve filters (cores, defaults), %d threads, best of %d runs\n", omp_get_max_threads(), repeat);
  std::printf("%-10s %-32s %9s %12s %10s %10s\n", "faces", "filter core", "time s", "s / M faces", "peak MiB",
              "segments");
  for (long target : sizes) {
    // A raised and a sunken disc on a cylinder, 10 % normal noise, about `target` faces.
    rktest::ReliefShape shape;
    shape.noise = 0.1;
    const int nz = std::max(8, int(std::sqrt(target / 2.0 / M_PI)));
    const int nu = std::max(8, int(target / 2 / nz));
    TriMesh m = rktest::discs_on_cylinder(shape, nu, nz).mesh;
    std::map<std::string, double> relief_stages;
    const std::pair<const char*, std::function<size_t()>> runs[] = {
        {"Demarcating Curves",
         [&] {
           DemarcatingParams p;
           return compute_demarcating(m, p).curves.segments.size();
         }},
        {"Relief Edges (with base normals)",
         [&] {
           ReliefEdgeParams p;
           p.progress = progress;
           return compute_relief_edges(m, p).edges.segments.size();
         }},
        {"Ridges and Valleys",
         [&] {
           RidgeValleyResult r = compute_ridges_valleys(m);
           return r.ridges.segments.size() + r.valleys.segments.size();
         }}};
    for (const auto& [name, fn] : runs) {
      double best = 1e30;
      long peak = 0;
      size_t segs = 0;
      for (int r = 0; r < repeat; ++r) {
        long base = status_kb("VmRSS:");
        std::ofstream("/proc/self/clear_refs") << "5";
        stage_time.clear();
        stage.clear();
        double t0 = now();
        stage_start = t0;
        segs = fn();
        double t = now() - t0;
        progress(100, "");
        if (t < best) {
          best = t;
          if (!stage_time.empty()) relief_stages = stage_time;
        }
        peak = std::max(peak, status_kb("VmHWM:") - base);
      }
      std::printf("%-10d %-32s %9.3f %12.3f %10.0f %10zu\n", m.n_faces(), name, best, best / (m.n_faces() / 1e6),
                  peak / 1024.0, segs);
    }
    std::printf("  relief-edge stages (best run):\n");
    for (const auto& kv : relief_stages)
      if (!kv.first.empty()) std::printf("    %-26s %.3f s\n", kv.first.c_str(), kv.second);
  }
  return 0;
}
