// ReliefKit — OpenMP threads that wait without taking a core. See openmp_waiting.h.
#include "reliefkit/base/openmp_waiting.h"

#include <dlfcn.h>
#include <omp.h>

#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>

namespace reliefkit {
namespace {

constexpr const char* kMark = "RELIEFKIT_OPENMP_WAITING";

// The library this code's OpenMP calls go to (LLVM's libomp, which clang builds use, also answers
// to GOMP_* names, but spins for its own block time).
bool runtime_is_libgomp() {
  Dl_info info{};
  return dladdr(reinterpret_cast<void*>(&omp_get_num_threads), &info) != 0 && info.dli_fname &&
         std::strstr(info.dli_fname, "libgomp") != nullptr;
}

// A thread that runs one team of two and then sleeps for good: its pool keeps the team's second
// thread, docked and asleep, counted among the threads libgomp manages. (The team must do
// something: GCC drops an empty parallel region.) False when the team got one thread.
bool park_one_team_of_two() {
  std::mutex m;
  std::condition_variable started;
  bool ready = false;
  int team = 0;
  std::thread([&] {
#pragma omp parallel num_threads(2)
    {
#pragma omp single
      team = omp_get_num_threads();
    }
    {
      std::lock_guard<std::mutex> lock(m);  // the caller returns only once this is released
      ready = true;
      started.notify_one();
    }
    std::mutex forever;
    std::unique_lock<std::mutex> hold(forever);
    std::condition_variable never;
    never.wait(hold, [] { return false; });
  }).detach();
  std::unique_lock<std::mutex> lock(m);
  started.wait(lock, [&] { return ready; });
  return team == 2;
}

}  // namespace

bool wait_passively_in_openmp() {
  static std::mutex once;
  std::lock_guard<std::mutex> lock(once);
  if (std::getenv(kMark)) return true;
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT") || !runtime_is_libgomp()) return false;
  if (!park_one_team_of_two()) return false;
  setenv(kMark, "1", 1);
  return true;
}

}  // namespace reliefkit
