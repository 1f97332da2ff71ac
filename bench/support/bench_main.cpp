// Google Benchmark main with MPI and Kokkos alive for the whole run. Every rank runs every
// benchmark (they are collective), but only rank 0 reports: the others print nothing and
// write no --benchmark_out file.
#include <benchmark/benchmark.h>
#include "parallel/mpi.hpp"

#include <Kokkos_Core.hpp>
#include <cstring>

namespace {

// Swallows every report: the ranks other than 0 run the benchmarks silently.
class NullReporter : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>&) override {}
  void Finalize() override {}
};

// Drops --benchmark_out=... and --benchmark_out_format=... so that a non-root rank does not
// open (and truncate) rank 0's output file.
void drop_output_flags(int* argc, char** argv) {
  int kept = 1;
  for (int a = 1; a < *argc; ++a) {
    if (std::strncmp(argv[a], "--benchmark_out", 15) == 0) continue;
    argv[kept++] = argv[a];
  }
  *argc = kept;
  argv[kept] = nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  {
    Kokkos::ScopeGuard kokkos(argc, argv);
    if (rank != 0) drop_output_flags(&argc, argv);
    benchmark::Initialize(&argc, argv);
    if (rank == 0) {
      benchmark::RunSpecifiedBenchmarks();
    } else {
      NullReporter quiet;
      benchmark::RunSpecifiedBenchmarks(&quiet);
    }
    benchmark::Shutdown();
  }
  MPI_Finalize();
  return 0;
}
