#include "reliefkit/base/work_counts.h"

#include <atomic>

namespace reliefkit {
namespace {
std::atomic<long long> g_counts[static_cast<int>(Work::Count_)];
}

void count_work(Work w) { g_counts[static_cast<int>(w)].fetch_add(1, std::memory_order_relaxed); }

WorkCounts work_counts() {
  WorkCounts c;
  for (int i = 0; i < static_cast<int>(Work::Count_); ++i) c.n[i] = g_counts[i].load(std::memory_order_relaxed);
  return c;
}

void reset_work_counts() {
  for (auto& c : g_counts) c.store(0, std::memory_order_relaxed);
}

std::string WorkCounts::summary() const {
  static const char* const names[] = {"adjacency", "scale", "noise", "Laplacian", "noise floor", "repair", "curvature"};
  std::string s;
  for (int i = 0; i < static_cast<int>(Work::Count_); ++i)
    s += (i ? ", " : "") + std::string(names[i]) + " " + std::to_string(n[i]);
  return s;
}

}  // namespace reliefkit
