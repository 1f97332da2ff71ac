// STREAM-like triad a = b + s c over three 64 MiB Kokkos Views (8 Mi doubles each, far above
// any cache): the machine's sustainable memory bandwidth, to set beside every kernel's GB/s.
//
// GB/s counts 24 bytes per element (read b, read c, write a) as STREAM does. It does NOT
// count write-allocate: without streaming stores the CPU first reads each line of `a` it is
// about to overwrite, so the bus really moves 32 bytes per element; GB/s_with_write_allocate
// reports that (= GB/s x 4/3) for comparison with kernels whose bytes are counted the same way.
#include <benchmark/benchmark.h>
#include "parallel/mpi.hpp"

#include <chrono>
#include <string>

#include "core/compat.hpp"
#include "core/types.hpp"

namespace {
using namespace eulerfsi;

void BM_Triad(benchmark::State& state) {
  const long n = state.range(0) * (1L << 20) / long(sizeof(double));  // range(0) MiB per array
  using Vec = Kokkos::View<double*, MemSpace>;
  Vec a("a", n), b("b", n), c("c", n);
  const double s = 3.0;
  const Kokkos::RangePolicy<ExecSpace> policy(0, n);
  // first touch by the same threads that will stream the arrays (NUMA-friendly on bigger boxes)
  Kokkos::parallel_for("eulerfsi::bench::triad_init", policy, KOKKOS_LAMBDA(const long i) {
    a(i) = 0.0;
    b(i) = 1.0;
    c(i) = 2.0;
  });
  compat::fence();

  double total_s = 0.0;
  for (auto _ : state) {
    MPI_Barrier(MPI_COMM_WORLD);
    const auto t0 = std::chrono::steady_clock::now();
    Kokkos::parallel_for("eulerfsi::bench::triad", policy, KOKKOS_LAMBDA(const long i) { a(i) = b(i) + s * c(i); });
    compat::fence();
    double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    MPI_Allreduce(MPI_IN_PLACE, &dt, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    state.SetIterationTime(dt);
    total_s += dt;
  }
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  // every rank streams its own arrays: the aggregate bandwidth is ranks x the per-rank traffic
  const double bytes = 24.0 * double(n) * ranks * double(state.iterations());
  state.counters["GB/s"] = benchmark::Counter(1e-9 * bytes / total_s);
  state.counters["GB/s_with_write_allocate"] = benchmark::Counter(1e-9 * bytes * 4.0 / 3.0 / total_s);
  state.counters["ns_per_element"] = benchmark::Counter(1e9 * total_s / (double(n) * double(state.iterations())));
  state.counters["threads"] = benchmark::Counter(ExecSpace().concurrency());
  state.SetLabel(std::string(compat::default_backend_name()));
}

BENCHMARK(BM_Triad)->ArgName("MiB_per_array")->Arg(64)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
