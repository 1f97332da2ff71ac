// Cost of one pressure Poisson solve (gather, forward r2r, eigenvalue division, backward,
// scatter) on duct-like grids (y, z walls), as ns per cell of the global grid.
// Run on more ranks with mpiexec: the time is the slowest rank's.
#include <benchmark/benchmark.h>
#include "parallel/mpi.hpp"

#include <chrono>
#include <memory>
#include <string>

#include "core/compat.hpp"
#include "grid/grid.hpp"
#include "poisson/fft_dct_poisson.hpp"
#include "poisson/poisson_solver.hpp"
#ifdef EULERFSI_HAVE_MPI
#include "poisson/fftw_mpi_poisson.hpp"
#endif

namespace {
using namespace eulerfsi;

// solver: 0 the build's default, 1 FFTW-MPI with measured plans, 2 FFT_DCT (one rank)
void solve_loop(benchmark::State& state, int solver_kind) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const int cells[3] = {int(state.range(0)), int(state.range(1)), int(state.range(2))};
  const double len[3] = {double(cells[0]) / cells[1], 1.0, 1.0};  // unit cross-section, cubic cells
  const Grid g(cells, len, Boundary::Wall, Boundary::Wall, rank, size);
  if (solver_kind == 2 && size > 1) {
    state.SkipWithError("FFT_DCT runs on one rank");
    return;
  }
  std::unique_ptr<PoissonSolver> solver;
  if (solver_kind == 2) solver = std::make_unique<FftDctPoisson>(g);
#ifdef EULERFSI_HAVE_MPI
  if (solver_kind == 1) solver = std::make_unique<FftwMpiPoisson>(g, MPI_COMM_WORLD, FftwMpiPoisson::Planning::Measure);
#endif
  if (!solver) solver = make_poisson_solver(g, MPI_COMM_WORLD);

  Field3 rhs = g.make_field("rhs");
  Field3 phi = g.make_field("phi");
  // f = a smooth mode plus a rough one: all of the spectrum is busy, as after a real predictor
  Kokkos::parallel_for(
      "eulerfsi::bench::poisson_rhs", g.interior().policy(), KOKKOS_LAMBDA(const int i, const int j, const int k) {
        rhs(i, j, k) = compat::sin(0.3 * i + 0.1) * compat::cos(0.2 * j) + ((i * 7 + j * 13 + k * 5) % 11) * 0.01;
      });

  double total_s = 0.0;
  for (auto _ : state) {
    // a fresh rhs every time: solving on the previous phi would shrink it towards denormals
    Kokkos::deep_copy(phi, rhs);
    compat::fence();
    MPI_Barrier(MPI_COMM_WORLD);
    const auto t0 = std::chrono::steady_clock::now();
    solver->solve(phi);
    compat::fence();
    double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    MPI_Allreduce(MPI_IN_PLACE, &dt, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    state.SetIterationTime(dt);
    total_s += dt;
  }
  const double cells_total = double(g.global_cells());
  state.counters["ns_per_cell"] = benchmark::Counter(1e9 * total_s / (double(state.iterations()) * cells_total));
  state.counters["Mcells_per_s"] =
      benchmark::Counter(1e-6 * cells_total * double(state.iterations()) / total_s);
  state.counters["ranks"] = benchmark::Counter(size);
  state.SetLabel(std::string(solver->name()) + (solver_kind == 1 ? " measure " : " ") + compat::default_backend_name());
}

// the 4th argument asks FFTW-MPI to measure plans instead of estimating them (the default)
void BM_PoissonSolve(benchmark::State& state) { solve_loop(state, state.range(3) ? 1 : 0); }
void BM_PoissonFftDct(benchmark::State& state) { solve_loop(state, 2); }

BENCHMARK(BM_PoissonSolve)
    ->ArgNames({"nx", "ny", "nz", "measure"})
    ->Args({32, 32, 32, 0})
    ->Args({64, 64, 64, 0})
    ->Args({128, 64, 64, 0})
    ->Args({64, 64, 64, 1})
    ->Args({128, 64, 64, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// r2c FFT + Makhoul DCT kernels around batched 1-D transforms (FFTW here, cuFFT/hipFFT on GPUs)
BENCHMARK(BM_PoissonFftDct)
    ->ArgNames({"nx", "ny", "nz"})
    ->Args({32, 32, 32})
    ->Args({64, 64, 64})
    ->Args({128, 64, 64})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
