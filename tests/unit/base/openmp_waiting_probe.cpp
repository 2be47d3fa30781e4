// The parked OpenMP thread of reliefkit/base/openmp_waiting.h against libgomp's default spinning,
// in a process started with neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT (tests/CMakeLists.txt).
// Short parallel loops with 2 ms pauses between them, as a filter's stages leave them: the CPU
// time the process uses beyond the loops' own work is what its waiting threads spun. Exit status
// 0 when parking cut that to under a quarter and libgomp had spun at all; the figures printed.
#include <omp.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include "reliefkit/base/openmp_waiting.h"

namespace {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// CPU seconds over 200 rounds of a short loop on every thread and a 2 ms pause.
double cpu_of_short_loops_with_pauses(std::vector<double>& sink) {
  const double before = cpu_seconds();
  for (int round = 0; round < 200; ++round) {
#pragma omp parallel for schedule(static)
    for (int i = 0; i < int(sink.size()); ++i) sink[size_t(i)] += 1e-9 * i;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return cpu_seconds() - before;
}

}  // namespace

int main() {
  std::vector<double> sink(1 << 12);
  const int threads = omp_get_max_threads();
  const double spinning = cpu_of_short_loops_with_pauses(sink);
  const bool parked = reliefkit::wait_passively_in_openmp();
  const double passive = cpu_of_short_loops_with_pauses(sink);
  std::printf("%d threads; CPU of 200 short loops with 2 ms pauses: %.3f s spinning (libgomp's default), "
              "%.3f s with one OpenMP thread parked (%s)\n", threads, spinning, passive, parked ? "parked" : "not parked");
  if (threads < 2) return std::printf("one thread: nothing waits, nothing to compare\n"), 0;
  const bool ok = parked && spinning > 0.1 && passive < 0.25 * spinning;
  std::printf("%s\n", ok ? "PASS" : "FAIL: the waiting threads still spin");
  return ok ? 0 : 1;
}
