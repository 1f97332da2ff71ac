// A Kokkos Tools library that times every named kernel and deep copy and prints, at the end of
// the program, each one's total, calls and share of the time spent in kernels. Load it with
//   KOKKOS_TOOLS_LIBS=build/bench/libeulerfsi_kernel_timer.so (Kokkos >= 4)
//   KOKKOS_PROFILE_LIBRARY=build/bench/libeulerfsi_kernel_timer.so (Kokkos 3.4)
// e.g. around `eulerfsi run` or bench_step. The wall time outside Kokkos kernels (FFTW, MPI,
// host loops) is the program's time minus the sum printed here. Only the Kokkos Tools C
// interface is used (no Kokkos header), so the library works with any Kokkos version.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct Entry {
  double seconds = 0.0;
  long calls = 0;
};

struct Open {
  std::string name;
  Clock::time_point start;
};

std::map<std::string, Entry>& table() {
  static std::map<std::string, Entry> t;
  return t;
}
std::vector<Open>& open_regions() {
  static std::vector<Open> o;
  return o;
}
Clock::time_point& program_start() {
  static Clock::time_point t = Clock::now();
  return t;
}

void begin(const std::string& name, uint64_t* id) {
  open_regions().push_back({name, Clock::now()});
  *id = open_regions().size() - 1;
}

void end(uint64_t id) {
  auto& o = open_regions();
  if (id + 1 != o.size()) return;  // kernels do not nest on one thread; ignore anything odd
  Entry& e = table()[o.back().name];
  e.seconds += std::chrono::duration<double>(Clock::now() - o.back().start).count();
  ++e.calls;
  o.pop_back();
}

}  // namespace

struct SpaceHandle {
  char name[64];
};

extern "C" {

void kokkosp_init_library(int, uint64_t, uint32_t, void*) { program_start(); }

void kokkosp_finalize_library() {
  std::vector<std::pair<std::string, Entry>> rows(table().begin(), table().end());
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  double total = 0.0;
  for (const auto& r : rows) total += r.second.seconds;
  const double wall = std::chrono::duration<double>(Clock::now() - program_start()).count();
  std::printf("\nkernel timer: %.3f s in Kokkos kernels and copies of %.3f s wall\n", total, wall);
  std::printf("%10s %8s %6s  %s\n", "seconds", "calls", "share", "kernel");
  for (const auto& [name, e] : rows)
    std::printf("%10.4f %8ld %5.1f%%  %s\n", e.seconds, e.calls, 100.0 * e.seconds / total, name.c_str());
}

void kokkosp_begin_parallel_for(const char* name, uint32_t, uint64_t* id) { begin(name, id); }
void kokkosp_end_parallel_for(uint64_t id) { end(id); }
void kokkosp_begin_parallel_reduce(const char* name, uint32_t, uint64_t* id) { begin(name, id); }
void kokkosp_end_parallel_reduce(uint64_t id) { end(id); }
void kokkosp_begin_parallel_scan(const char* name, uint32_t, uint64_t* id) { begin(name, id); }
void kokkosp_end_parallel_scan(uint64_t id) { end(id); }

void kokkosp_begin_deep_copy(SpaceHandle, const char* dst, const void*, SpaceHandle, const char* src, const void*,
                             uint64_t) {
  uint64_t id;
  begin(std::string("deep_copy ") + src + " -> " + dst, &id);
}
void kokkosp_end_deep_copy() { end(open_regions().empty() ? 0 : open_regions().size() - 1); }

}  // extern "C"
