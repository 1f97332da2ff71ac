// Cost of one whole RK3 time step (three substeps: momentum rhs, predictor, projection with the
// Poisson solve, flow-rate correction, ghost fills; with a particle also the psi/B transport,
// mixture viscosity and elastic force) of a laminar pipe flow at Re = 100, as ns per cell per
// step of the global grid. Cells are cubic: length [Nx/Ny, 1, 1]. The particle is the quick
// start's sphere, d = 0.2 at r/R = 0.2828, We = 1. The time is the slowest rank's.
#include <benchmark/benchmark.h>
#include "parallel/mpi.hpp"

#include <chrono>
#include <string>

#include "app/simulation.hpp"
#include "support/pipe_case.hpp"
#include "config/case_config.hpp"
#include "core/compat.hpp"
#include "parallel/comm.hpp"
#include "solid/solid_phase.hpp"
#include "solver/flow_solver.hpp"

namespace {
using namespace eulerfsi;

using bench::pipe_case;
using bench::pipe_case_bodies;

// The timed steps of one case; the label names it.
void time_steps(benchmark::State& state, const CaseConfig& cfg, const std::string& label) {
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  FlowSolver flow(cfg, grid, comm);
  SolidPhase solids(cfg, grid, flow.boundaries(), comm);
  flow.set_initial_condition();
  solids.set_initial_condition();
  if (!solids.empty()) {
    solids.stop_bodies_at_rest(flow.state().vel);
    flow.make_solenoidal();
  }
  SolidPhase* solid_ptr = solids.empty() ? nullptr : &solids;
  // one fixed, stable step: the work per step does not depend on dt
  const double dt = flow.stable_dt(solids.max_wave_speed());
  double t = 0.0;
  flow.advance(t, dt, solid_ptr);  // warm-up: first touch, FFTW plan caches
  t += dt;
  compat::fence();

  double total_s = 0.0;
  for (auto _ : state) {
    MPI_Barrier(comm.comm);
    const auto t0 = std::chrono::steady_clock::now();
    flow.advance(t, dt, solid_ptr);
    compat::fence();
    double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    MPI_Allreduce(MPI_IN_PLACE, &sec, 1, MPI_DOUBLE, MPI_MAX, comm.comm);
    state.SetIterationTime(sec);
    total_s += sec;
    t += dt;
  }
  const double cells = double(grid.global_cells());
  const double steps = double(state.iterations());
  state.counters["ns_per_cell_step"] = benchmark::Counter(1e9 * total_s / (steps * cells));
  state.counters["cells_per_second"] = benchmark::Counter(cells * steps / total_s);
  state.counters["threads"] = benchmark::Counter(ExecSpace().concurrency());
  state.counters["ranks"] = benchmark::Counter(comm.size());
  state.SetLabel(label + compat::default_backend_name());
}

// implicit: time.implicit_viscosity (three Helmholtz solves per substep besides the Poisson one)
void step_benchmark(benchmark::State& state, bool implicit) {
  // particle: 0 none, 1 the paper's model, 2 the reference map
  const bool particle = state.range(3) != 0;
  const SolidModelKind model = state.range(3) == 2 ? SolidModelKind::ReferenceMap : SolidModelKind::Paper;
  CaseConfig cfg = pipe_case(int(state.range(0)), int(state.range(1)), int(state.range(2)), particle, model);
  cfg.time.implicit_viscosity = implicit;
  static const char* labels[3] = {"pipe ", "pipe+sphere(paper) ", "pipe+sphere(refmap) "};
  time_steps(state, cfg, std::string(labels[state.range(3)]) + (implicit ? "implicit-viscosity " : ""));
}

void BM_Step(benchmark::State& state) { step_benchmark(state, false); }

BENCHMARK(BM_Step)
    ->ArgNames({"nx", "ny", "nz", "particle"})
    ->Args({32, 32, 32, 0})
    ->Args({64, 64, 64, 0})
    ->Args({128, 64, 64, 0})
    ->Args({64, 64, 64, 1})
    ->Args({128, 64, 64, 1})
    ->Args({64, 64, 64, 2})
    ->Args({128, 64, 64, 2})
    ->Args({160, 80, 80, 0})
    ->Args({160, 80, 80, 1})
    ->Args({160, 80, 80, 2})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// The same step with time.implicit_viscosity: what the larger time step has to pay back.
void BM_StepImplicitViscosity(benchmark::State& state) { step_benchmark(state, true); }
BENCHMARK(BM_StepImplicitViscosity)
    ->ArgNames({"nx", "ny", "nz", "particle"})
    ->Args({64, 64, 64, 0})
    ->Args({128, 64, 64, 0})
    ->Args({128, 64, 64, 2})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// Several reference-map bodies (issue 8: their cost follows their number and size, not the grid):
// `bodies` spheres of diameter d_percent / 100 D spread along the pipe (pipe_case_bodies).
void BM_StepBodies(benchmark::State& state) {
  const int bodies = int(state.range(3));
  const double d = 0.01 * double(state.range(4));
  const CaseConfig cfg = pipe_case_bodies(int(state.range(0)), int(state.range(1)), int(state.range(2)), bodies, d);
  time_steps(state, cfg, "pipe+" + std::to_string(bodies) + "x sphere(refmap, d=" + std::to_string(state.range(4)) + "%) ");
}
BENCHMARK(BM_StepBodies)
    ->ArgNames({"nx", "ny", "nz", "bodies", "d_percent"})
    ->Args({128, 64, 64, 1, 20})
    ->Args({128, 64, 64, 2, 20})
    ->Args({128, 64, 64, 4, 20})
    ->Args({128, 64, 64, 1, 10})
    ->Args({128, 64, 64, 4, 10})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// GPU sizes (ci/gpu): 128^3, 256 x 128^2 and 480 x 160^2 (two thirds of the paper's 720 x 240^2
// in every direction, 12.3 of its 41.5 M cells); seconds per step on a CPU, so
// bench/run_benchmarks.sh leaves them out.
void BM_StepLarge(benchmark::State& state) { BM_Step(state); }
BENCHMARK(BM_StepLarge)
    ->ArgNames({"nx", "ny", "nz", "particle"})
    ->Args({128, 128, 128, 0})
    ->Args({256, 128, 128, 0})
    ->Args({480, 160, 160, 0})
    ->Args({128, 128, 128, 1})
    ->Args({256, 128, 128, 1})
    ->Args({480, 160, 160, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
