// Shared helpers of the benchmark programs: wall clock, resident memory, per-stage timing from
// the cores' progress callback, and the --sizes / --repeat command line.
#pragma once

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "mesh_files.h"

namespace rkbench {

/// Reads a scan for a benchmark; says so and returns false when it cannot.
inline bool read_scan(const std::string& path, reliefkit::TriMesh& mesh) {
  try {
    mesh = rktest::read_mesh(path).mesh;
    return true;
  } catch (const std::exception& e) {
    std::printf("%s: not read (%s)\n", path.c_str(), e.what());
    return false;
  }
}

inline double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// A field of /proc/self/status in KiB ("VmRSS:", "VmHWM:").
inline long status_kb(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key, 0) == 0) return std::stol(line.substr(std::strlen(key)));
  return -1;
}

/// Peak resident memory growth of a measured section: start() resets the kernel's high-water
/// mark, grown_mib() reads how far it rose above the resident size at start().
struct PeakMemory {
  long base = 0;
  void start() {
    base = status_kb("VmRSS:");
    std::ofstream("/proc/self/clear_refs") << "5";
  }
  double grown_mib() const { return (status_kb("VmHWM:") - base) / 1024.0; }
};

/// Time spent between successive progress reports, by label.
struct Stages {
  std::map<std::string, double> time;
  std::string current;
  double since = 0;
  void start() { time.clear(), current.clear(), since = now(); }
  void report(const char* what) {
    double t = now();
    if (!current.empty()) time[current] += t - since;
    current = what;
    since = t;
  }
};
inline Stages g_stages;
inline bool stage_progress(int, const char* what) {
  g_stages.report(what);
  return true;
}

struct Args {
  std::vector<long> sizes;
  int repeat = 3;
};
inline Args parse_args(int argc, char** argv, std::vector<long> default_sizes) {
  Args a{std::move(default_sizes), 3};
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--sizes")) {
      a.sizes.clear();
      std::stringstream ss(argv[i + 1]);
      std::string tok;
      while (std::getline(ss, tok, ',')) a.sizes.push_back(std::stol(tok));
    } else if (!std::strcmp(argv[i], "--repeat")) {
      a.repeat = std::atoi(argv[i + 1]);
    }
  }
  return a;
}

}  // namespace rkbench
