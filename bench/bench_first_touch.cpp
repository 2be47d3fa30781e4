// What memory new to a process costs on this machine: 256 MiB mapped and written one byte per
// 4 KiB page, with 4 KiB pages and with huge pages advised (MADV_HUGEPAGE), each twice. On a
// virtual machine with shadow paging the first write to a page costs microseconds, and whether
// huge pages are cheap depends on the free memory the guest has at hand — which is why the first
// ReliefKit filter of a process is slower than the same filter later (docs/benchmarks.md).
//   build/bench/bench_first_touch
#include <sys/mman.h>

#include <chrono>
#include <cstdio>
#include <initializer_list>

namespace {

double seconds_to_touch(size_t bytes, bool huge) {
  char* p = static_cast<char*>(mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0));
  if (p == MAP_FAILED) return -1;
  if (huge) madvise(p, bytes, MADV_HUGEPAGE);
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < bytes; i += 4096) p[i] = 1;
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  munmap(p, bytes);
  return s;
}

}  // namespace

int main() {
  constexpr size_t kBytes = size_t(256) << 20;
  std::printf("first write to 256 MiB of new memory, one byte per 4 KiB page\n");
  for (int round = 1; round <= 2; ++round)
    for (bool huge : {false, true}) {
      const double s = seconds_to_touch(kBytes, huge);
      std::printf("round %d  %-22s %.3f s  (%.2f us per 4 KiB page)\n", round,
                  huge ? "huge pages advised" : "4 KiB pages", s, s * 1e6 / (kBytes / 4096));
    }
}
