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

// A case set up as a run starts, stepped with one fixed, stable dt (the work per step does not
// depend on dt); step() returns the seconds of one step, the slowest rank's.
struct SteppedCase {
  Comm comm;
  Grid grid;
  FlowSolver flow;
  SolidPhase solids;
  SolidPhase* solid_ptr = nullptr;
  double dt = 0.0, t = 0.0;

  explicit SteppedCase(const CaseConfig& cfg)
      : grid(make_grid(cfg, comm)), flow(cfg, grid, comm), solids(cfg, grid, flow.boundaries(), comm) {
    flow.set_initial_condition();
    solids.set_initial_condition();
    if (!solids.empty()) {
      solids.stop_bodies_at_rest(flow.state().vel);
      flow.make_solenoidal();
      solid_ptr = &solids;
    }
    dt = flow.stable_dt(solids.max_wave_speed());
    flow.advance(t, dt, solid_ptr);  // warm-up: first touch, FFTW plan caches
    t += dt;
    compat::fence();
  }

  double step() {
    MPI_Barrier(comm.comm);
    const auto t0 = std::chrono::steady_clock::now();
    flow.advance(t, dt, solid_ptr);
    compat::fence();
    double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    MPI_Allreduce(MPI_IN_PLACE, &sec, 1, MPI_DOUBLE, MPI_MAX, comm.comm);
    t += dt;
    return sec;
  }
};

// The timed steps of one case; the label names it.
void time_steps(benchmark::State& state, const CaseConfig& cfg, const std::string& label) {
  SteppedCase run(cfg);
  const Grid& grid = run.grid;
  double total_s = 0.0;
  for (auto _ : state) {
    const double sec = run.step();
    state.SetIterationTime(sec);
    total_s += sec;
  }
  const double cells = double(grid.global_cells());
  const double steps = double(state.iterations());
  state.counters["ns_per_cell_step"] = benchmark::Counter(1e9 * total_s / (steps * cells));
  state.counters["cells_per_second"] = benchmark::Counter(cells * steps / total_s);
  state.counters["threads"] = benchmark::Counter(ExecSpace().concurrency());
  state.counters["ranks"] = benchmark::Counter(run.comm.size());
  state.SetLabel(label + compat::default_backend_name());
}

// implicit: time.implicit_viscosity (three Helmholtz solves per substep besides the Poisson one)
void step_benchmark(benchmark::State& state, bool implicit) {
  // particle: 0 none, 1 the paper's model, 2 the reference map, 3 a rigid sphere, 4 a rigid sphere
  // whose correction the next step's projection makes divergence-free (solver.reproject_constrained = false)
  const bool particle = state.range(3) != 0;
  const SolidModelKind kinds[5] = {SolidModelKind::Paper, SolidModelKind::Paper, SolidModelKind::ReferenceMap,
                                   SolidModelKind::Rigid, SolidModelKind::Rigid};
  const SolidModelKind model = kinds[state.range(3)];
  CaseConfig cfg = pipe_case(int(state.range(0)), int(state.range(1)), int(state.range(2)), particle, model);
  cfg.time.implicit_viscosity = implicit;
  cfg.solver.reproject_constrained = state.range(3) != 4;
  static const char* labels[5] = {"pipe ", "pipe+sphere(paper) ", "pipe+sphere(refmap) ", "pipe+sphere(rigid) ",
                                  "pipe+sphere(rigid, no reprojection) "};
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
    ->Args({128, 64, 64, 3})
    ->Args({128, 64, 64, 4})
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

// The flow alone and the same flow with reference-map bodies (`bodies` spheres of diameter
// d_percent / 100 D spread along the pipe, pipe_case_bodies; 1 x 20 % is BM_Step's particle), one
// step of each in turn: their ratio (x_flow) comes from the same minutes of the machine, so a
// shared VM's drift, which moves separate benchmarks by 10-30 %, cancels. The iteration time is
// the pair's. Issue 8: the bodies' cost follows their number and size, not the grid.
// One step of each case in turn; the counters and the pair's iteration time.
void time_pair(benchmark::State& state, const CaseConfig& flow_cfg, const CaseConfig& bodies_cfg, int warmup = 0) {
  SteppedCase flow_only(flow_cfg);
  SteppedCase with_bodies(bodies_cfg);
  for (int n = 0; n < warmup; ++n) with_bodies.step();
  double flow_s = 0.0, bodies_s = 0.0;
  for (auto _ : state) {
    const double a = flow_only.step(), b = with_bodies.step();
    flow_s += a;
    bodies_s += b;
    state.SetIterationTime(a + b);
  }
  const double cells = double(flow_only.grid.global_cells()), steps = double(state.iterations());
  state.counters["flow_ns_per_cell_step"] = benchmark::Counter(1e9 * flow_s / (steps * cells));
  state.counters["particle_ns_per_cell_step"] = benchmark::Counter(1e9 * bodies_s / (steps * cells));
  state.counters["x_flow"] = benchmark::Counter(bodies_s / flow_s);
  state.counters["threads"] = benchmark::Counter(ExecSpace().concurrency());
  state.counters["ranks"] = benchmark::Counter(flow_only.comm.size());
}

void step_pair(benchmark::State& state, FftPlanning planning) {
  const int nx = int(state.range(0)), ny = int(state.range(1)), nz = int(state.range(2));
  const int bodies = int(state.range(3));
  CaseConfig flow_cfg = pipe_case(nx, ny, nz, false);
  CaseConfig bodies_cfg = pipe_case_bodies(nx, ny, nz, bodies, 0.01 * double(state.range(4)));
  flow_cfg.solver.fft_planning = bodies_cfg.solver.fft_planning = planning;
  time_pair(state, flow_cfg, bodies_cfg);
  state.SetLabel("pipe, then pipe+" + std::to_string(bodies) + "x sphere(refmap, d=" + std::to_string(state.range(4)) +
                 "%) " + (planning == FftPlanning::Measure ? "measured FFT plans " : "") +
                 compat::default_backend_name());
}
// Issue 8's two grids, one body of d = D/5.
void pair_grids(benchmark::internal::Benchmark* b) {
  b->ArgNames({"nx", "ny", "nz", "bodies", "d_percent"})
      ->Args({128, 64, 64, 1, 20})
      ->Args({160, 80, 80, 1, 20})
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
}
void BM_StepPair(benchmark::State& state) { step_pair(state, FftPlanning::Estimate); }
BENCHMARK(BM_StepPair)->Apply(pair_grids);
// The same pair with FFTW_MEASURE plans ([solver] fft_planning = "measure", as cases/desk and
// cases/paper run): the flow step is ~8-12 % cheaper, the particle's share correspondingly larger.
void BM_StepPairMeasuredPlans(benchmark::State& state) { step_pair(state, FftPlanning::Measure); }
BENCHMARK(BM_StepPairMeasuredPlans)->Apply(pair_grids);
// the same with several and smaller bodies (one grid; bench/run_benchmarks.sh runs them on 1 core)
void BM_StepPairBodies(benchmark::State& state) { step_pair(state, FftPlanning::Estimate); }
BENCHMARK(BM_StepPairBodies)
    ->ArgNames({"nx", "ny", "nz", "bodies", "d_percent"})
    ->Args({128, 64, 64, 2, 20})
    ->Args({128, 64, 64, 4, 20})
    ->Args({128, 64, 64, 1, 10})
    ->Args({128, 64, 64, 4, 10})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// The flow alone and the flow with BM_Step's rigid sphere (d = D/5), a step of each in turn;
// reproject: solver.reproject_constrained (1: the second projection after the correction, 0: left
// to the next step's). Issue 29's bound: at most 1.1x the flow on 128 x 64^2.
void BM_StepPairRigid(benchmark::State& state) {
  const int nx = int(state.range(0)), ny = int(state.range(1)), nz = int(state.range(2));
  CaseConfig flow_cfg = pipe_case(nx, ny, nz, false);
  CaseConfig rigid_cfg = pipe_case(nx, ny, nz, true, SolidModelKind::Rigid);
  rigid_cfg.solver.reproject_constrained = state.range(3) != 0;
  time_pair(state, flow_cfg, rigid_cfg);
  state.SetLabel(std::string("pipe, then pipe+sphere(rigid") + (state.range(3) ? "" : ", no reprojection") + ") " +
                 compat::default_backend_name());
}
BENCHMARK(BM_StepPairRigid)
    ->ArgNames({"nx", "ny", "nz", "reproject"})
    ->Args({128, 64, 64, 1})
    ->Args({128, 64, 64, 0})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// The flow alone and the flow with BM_Step's paper-model sphere (d = D/5), a step of each in turn;
// warmup: steps the pair takes before the timed ones (the paper model's boxes follow psi's
// support, which its halo widens over the first steps). Issue 30's bound: at most 1.3x the flow on
// 128 x 64^2, on 1 and 2 threads.
void BM_StepPairPaper(benchmark::State& state) {
  const int nx = int(state.range(0)), ny = int(state.range(1)), nz = int(state.range(2));
  const CaseConfig flow_cfg = pipe_case(nx, ny, nz, false);
  const CaseConfig paper_cfg = pipe_case(nx, ny, nz, true, SolidModelKind::Paper);
  time_pair(state, flow_cfg, paper_cfg, int(state.range(3)));
  state.SetLabel(std::string("pipe, then pipe+sphere(paper) ") + compat::default_backend_name());
}
BENCHMARK(BM_StepPairPaper)
    ->ArgNames({"nx", "ny", "nz", "warmup"})
    ->Args({128, 64, 64, 0})
    ->Args({128, 64, 64, 200})
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
