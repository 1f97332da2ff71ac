// Each main kernel of the time step alone, on the fields of a real pipe case (laminar flow at
// Re = 100, cubic cells, length [Nx/Ny, 1, 1]; the solid kernels with the quick start's sphere
// d = 0.2 at r/R = 0.2828, We = 1, after one step so that B != I and psi has an interface).
//
// Counters: ns_per_cell (per call, per interior cell of the global grid; the particle's kernels:
// per cell of the box they run on, as the solver runs them on the body's window) and GB/s, an
// *effective* bandwidth: the minimal bytes the kernel must move (each field it reads or writes
// streamed exactly once, stencil neighbours from cache, no write-allocate, the 2D wall masks
// neglected) divided by the time. Compare it with bench_triad's GB/s (also counted without
// write-allocate): a memory-bound kernel that streams optimally sits near it, a kernel far
// below it is compute, latency or traffic bound (reads its fields several times).
// The Poisson solve is in bench_poisson. The time is the slowest rank's.
#include <benchmark/benchmark.h>
#include "parallel/mpi.hpp"

#include <chrono>
#include <string>

#include "app/simulation.hpp"
#include "support/pipe_case.hpp"
#include "config/case_config.hpp"
#include "core/compat.hpp"
#include "kernels/boundary.hpp"
#include "kernels/elastic_force.hpp"
#include "kernels/momentum.hpp"
#include "kernels/momentum_predictor.hpp"
#include "kernels/projection.hpp"
#include "kernels/solid_transport.hpp"
#include "kernels/time_update.hpp"
#include "parallel/comm.hpp"
#include "solid/solid_phase.hpp"
#include "solver/flow_solver.hpp"

namespace {
using namespace eulerfsi;

using bench::pipe_case;

// A pipe case ready to run: solenoidal laminar flow, and with a particle one step already taken.
struct PipeCase {
  Comm comm;
  CaseConfig cfg;
  Grid grid;
  FlowSolver flow;
  SolidPhase solids;

  PipeCase(const benchmark::State& state, bool particle)
      : cfg(pipe_case(int(state.range(0)), int(state.range(1)), int(state.range(2)), particle)),
        grid(make_grid(cfg, comm)), flow(cfg, grid, comm), solids(cfg, grid, flow.boundaries(), comm) {
    flow.set_initial_condition();
    solids.set_initial_condition();
    if (particle) {
      flow.make_solenoidal();
      flow.advance(0.0, flow.stable_dt(solids.max_wave_speed()), &solids);
    }
    compat::fence();
  }
  kernels::Velocity make_velocity(const char* label) const {
    return kernels::Velocity{{grid.make_field(label), grid.make_field(label), grid.make_field(label)}};
  }
};

// Times `kernel` (fenced, slowest rank) and sets ns_per_cell per `cells` (this rank's; default: the
// interior) and GB/s from `bytes_per_call` (this rank's; both summed over ranks).
template <class Kernel>
void time_kernel(benchmark::State& state, const Grid& g, double bytes_per_call, Kernel&& kernel, double cells = -1.0) {
  if (cells < 0.0) cells = double(g.interior().size());
  kernel();  // warm-up
  compat::fence();
  double total_s = 0.0;
  for (auto _ : state) {
    MPI_Barrier(MPI_COMM_WORLD);
    const auto t0 = std::chrono::steady_clock::now();
    kernel();
    compat::fence();
    double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    MPI_Allreduce(MPI_IN_PLACE, &sec, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    state.SetIterationTime(sec);
    total_s += sec;
  }
  MPI_Allreduce(MPI_IN_PLACE, &bytes_per_call, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &cells, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const double calls = double(state.iterations());
  state.counters["ns_per_cell"] = benchmark::Counter(1e9 * total_s / (calls * cells));
  state.counters["GB/s"] = benchmark::Counter(1e-9 * bytes_per_call * calls / total_s);
  state.counters["threads"] = benchmark::Counter(ExecSpace().concurrency());
  state.SetLabel(compat::default_backend_name());
}

// bytes of `doubles` per interior cell of this rank
double cell_bytes(const Grid& g, int doubles) { return 8.0 * doubles * double(g.interior().size()); }

// The body's fields live on a window around it (src/solid/solid_window.hpp): its transport runs
// on that window less the WENO5 stencil's 3 cells, cut to the interior (the solver's rhs box,
// psi's support grown by 3, lies inside it), with rhs buffers on the same window.
Box transport_box(const Grid& g, const WindowField& psi) {
  Box box = psi.window();
  for (int d = 0; d < 3; ++d) {
    box.lo[d] += 3;
    box.hi[d] -= 3;
  }
  return intersection(box, g.interior());
}
WindowField window_like(const WindowField& f, const char* label) {
  return WindowField(Field3(std::string(label), f.data.extent(0), f.data.extent(1), f.data.extent(2)), f.lo);
}

// momentum_rhs, 3 components in one sweep with the constant viscosity (the single-phase path, and
// everywhere outside a body's box). Minimal: read u, v, w; write rhs_u, rhs_v, rhs_w = 6 doubles.
void BM_MomentumRhs(benchmark::State& state) {
  PipeCase c(state, false);
  const auto rhs = c.make_velocity("rhs");
  const Box box = c.grid.interior();
  const double mu = 1.0 / c.cfg.flow.Re;
  time_kernel(state, c.grid, cell_bytes(c.grid, 6),
              [&] { kernels::momentum_rhs(rhs, c.flow.state().vel, mu, c.grid.h, box); });
}

// momentum_predict: the momentum right-hand side and the RK3 update in one pass (the solver's
// explicit predictor), the pipe's wall mask. Minimal: read u, v, w and rhs_old; write rhs and u*
// (over rhs_old) = 12 doubles (momentum_rhs alone: 6; the separate update it replaced: 12 more).
void BM_MomentumPredict(benchmark::State& state) {
  PipeCase c(state, false);
  const auto rhs = c.make_velocity("rhs");
  const auto rhs_old = c.make_velocity("rhs_old");
  const Box box = c.grid.interior();
  kernels::momentum_rhs(rhs_old, c.flow.state().vel, c.flow.viscosity(), c.grid.h, box);
  const double dt = 1e-6;
  kernels::PredictorTerms terms;
  terms.a = dt * 8.0 / 15.0;
  terms.penal = 0.3 * dt / 1e-8;
  for (int d = 0; d < 3; ++d) {
    terms.rhs_old_to_star[d] = rhs_old.c[d].data();
    terms.chi[d] = c.flow.masks().chi[d].data();
    terms.chi_stride[d] = long(c.flow.masks().chi[d].stride(0));
  }
  // u* over rhs_old every call: the same values each time (u does not change), as in a substep
  time_kernel(state, c.grid, cell_bytes(c.grid, 12),
              [&] { kernels::momentum_predict(rhs, c.flow.state().vel, 1.0 / c.cfg.flow.Re, c.grid.h, terms, box); });
}

// divergence as the solver calls it with a constant flow rate, summing the open faces' u in the
// same pass: read u, v, w; write div = 4 doubles.
void BM_Divergence(benchmark::State& state) {
  PipeCase c(state, false);
  const Field3 out = c.grid.make_field("div");
  const auto& u = c.flow.state().vel.c;
  double sum = 0.0;
  time_kernel(state, c.grid, cell_bytes(c.grid, 4), [&] {
    sum += kernels::divergence(out, u[0], u[1], u[2], c.grid.h, 1.0, c.grid.interior(), {kernels::Mask2(), true});
  });
  benchmark::DoNotOptimize(sum);
}

// subtract_gradient: read phi, u, v, w; write u, v, w = 7 doubles.
void BM_SubtractGradient(benchmark::State& state) {
  PipeCase c(state, false);
  const Field3 phi = c.grid.make_field("phi");
  const auto& u = c.flow.state().vel.c;
  // a realistic potential with its ghosts filled, as after the Poisson solve
  kernels::divergence(phi, u[0], u[1], u[2], c.grid.h, 1.0, c.grid.interior());
  c.flow.boundaries().fill_scalar(phi);
  time_kernel(state, c.grid, cell_bytes(c.grid, 7),
              [&] { kernels::subtract_gradient(u[0], u[1], u[2], phi, c.grid.h, 1e-6, c.grid.interior()); });
}

// subtract_gradient as the solver calls it, gathering the step pressure p_step += alpha phi (a
// middle substep: read p_step too) and adding the flow rate's uniform correction: read phi, u, v,
// w, p_step; write u, v, w, p_step = 9 doubles. It replaced two passes: one that read p and p_step
// and wrote p_step, one that read and wrote u (the flow-rate correction), on every cell.
void BM_SubtractGradientStepPressure(benchmark::State& state) {
  PipeCase c(state, false);
  const Field3 phi = c.grid.make_field("phi"), p_step = c.grid.make_field("p_step");
  const auto& u = c.flow.state().vel.c;
  kernels::divergence(phi, u[0], u[1], u[2], c.grid.h, 1.0, c.grid.interior());
  c.flow.boundaries().fill_scalar(phi);
  time_kernel(state, c.grid, cell_bytes(c.grid, 9), [&] {
    kernels::subtract_gradient(u[0], u[1], u[2], phi, c.grid.h, 1e-6, c.grid.interior(), {p_step, 0.2, false},
                               {kernels::Mask2(), 1e-9});
  });
}

// penalize_wall_layer for u, v, w: the pipe's interpolated wall on its first fluid layer (a list of
// (j, k) points, every x). Minimal: on each layer cell read u and its inner neighbour, write u =
// 3 doubles per layer cell (the layer is ~4 % of the cells at 128 x 64^2; ns_per_cell is per
// interior cell, like every other kernel).
void BM_PenalizeWallLayer(benchmark::State& state) {
  PipeCase c(state, false);
  const auto& vel = c.flow.state().vel.c;
  const auto& m = c.flow.masks();
  const Box box = c.grid.interior();
  double layer_cells = 0.0;
  for (int d = 0; d < 3; ++d) layer_cells += double(m.layer[d].extent(0)) * (box.hi[0] - box.lo[0]);
  time_kernel(state, c.grid, 8.0 * 3 * layer_cells, [&] {
    for (int d = 0; d < 3; ++d)
      kernels::penalize_wall_layer(vel[d], m.layer[d], m.weight[d], m.neighbour[d], 0.01, box, "wall_layer");
  });
}

// fill_ghosts of u, v, w in y and z with the pipe's wall rules (the kernel calls of
// BoundaryConditions::fill_velocity without the x halo exchange). Minimal: every ghost value
// written once from one owned value read: 2 doubles per ghost value, kGhost layers on each
// side of each wall direction. ns_per_cell is per interior cell, like every other kernel.
void BM_FillGhosts(benchmark::State& state) {
  PipeCase c(state, false);
  const Grid& g = c.grid;
  const auto& vel = c.flow.state().vel;
  const double e0 = g.ext(0), e1 = g.ext(1), e2 = g.ext(2);
  const double ghosts_per_component = 2.0 * kGhost * (e0 * e2 + e0 * e1);  // y slabs + z slabs
  time_kernel(state, g, 3 * ghosts_per_component * 2 * 8.0, [&] {
    for (int dir = 1; dir <= 2; ++dir)
      for (int d = 0; d < 3; ++d)
        kernels::fill_ghosts(vel.c[d], dir, g.n[dir], d == dir ? kernels::GhostRule::Normal : kernels::GhostRule::Tangent,
                             0.0, 0.0);
  });
}

// BoundaryConditions::fill_velocity: the x halo exchange (MPI, through host buffers; to itself
// on one rank) plus the y/z ghost kernels above. Minimal bytes: the y/z ghosts as above plus,
// per component, 2 kGhost x-planes of e1 x e2 read and written.
void BM_FillVelocity(benchmark::State& state) {
  PipeCase c(state, false);
  const Grid& g = c.grid;
  const double e0 = g.ext(0), e1 = g.ext(1), e2 = g.ext(2);
  const double ghosts_per_component = 2.0 * kGhost * (e0 * e2 + e0 * e1 + e1 * e2);
  time_kernel(state, g, 3 * ghosts_per_component * 2 * 8.0,
              [&] { c.flow.boundaries().fill_velocity(c.flow.state().vel, 0.0); });
}

// scalar_advection_rhs (WENO5 psi transport) on the body's transport box. Minimal: read psi,
// u, v, w; write rhs = 5 doubles per cell of the box.
void BM_ScalarAdvectionRhs(benchmark::State& state) {
  PipeCase c(state, true);
  const auto& body = c.solids.bodies()[0];
  const WindowField rhs = window_like(body.psi, "psi_rhs");
  const Box box = transport_box(c.grid, body.psi);
  time_kernel(
      state, c.grid, 8.0 * 5 * double(box.size()),
      [&] { kernels::scalar_advection_rhs(rhs, body.psi, c.flow.state().vel, c.grid.h, box); }, double(box.size()));
}

// tensor_transport_rhs (WENO5 advection + stretching of the six B components) on the body's
// transport box. Minimal: read 6 B, u, v, w, psi; write 6 rhs = 16 doubles per cell of the box.
void BM_TensorTransportRhs(benchmark::State& state) {
  PipeCase c(state, true);
  const auto& body = c.solids.bodies()[0];
  kernels::Tensor6 rhs;
  for (int s = 0; s < kernels::kTensorComponents; ++s) rhs.c[s] = window_like(body.b.c[s], "b_rhs");
  const Box box = transport_box(c.grid, body.psi);
  time_kernel(
      state, c.grid, 8.0 * 16 * double(box.size()),
      [&] { kernels::tensor_transport_rhs(rhs, body.b, c.flow.state().vel, body.psi, 1e-6, c.grid.h, box); },
      double(box.size()));
}

// add_elastic_force (one body, 3 components) on the faces the solver gives it
// (elastic_force_region). Minimal: read psi, 6 B, 6 B_prev, 3 rhs; write 3 rhs = 19 doubles per
// cell of that box. (As written: the shear stresses once, 7 read and 3 written, then one pass over
// the three components' faces reading psi, 3 B_DD, 3 B_prev_DD, the 3 shear stresses and 3 rhs and
// writing 3 rhs: 26 doubles.)
void BM_AddElasticForce(benchmark::State& state) {
  PipeCase c(state, true);
  const auto& body = c.solids.bodies()[0];
  const auto rhs = c.make_velocity("rhs");
  const Box faces = c.solids.elastic_force_region();
  time_kernel(
      state, c.grid, 8.0 * 19 * double(faces.size()),
      [&] {
        kernels::add_elastic_force(rhs, body.psi, body.b, body.b_prev, body.model->scratch(), body.G, c.grid.h, faces);
      },
      double(faces.size()));
}

#define EULERFSI_KERNEL_BENCH(fn)                                                                            \
  BENCHMARK(fn)->ArgNames({"nx", "ny", "nz"})->Args({64, 64, 64})->Args({128, 64, 64})->UseManualTime()->Unit( \
      benchmark::kMillisecond)

EULERFSI_KERNEL_BENCH(BM_MomentumRhs);
EULERFSI_KERNEL_BENCH(BM_MomentumPredict);
EULERFSI_KERNEL_BENCH(BM_Divergence);
EULERFSI_KERNEL_BENCH(BM_SubtractGradient);
EULERFSI_KERNEL_BENCH(BM_SubtractGradientStepPressure);
EULERFSI_KERNEL_BENCH(BM_PenalizeWallLayer);
EULERFSI_KERNEL_BENCH(BM_FillGhosts);
EULERFSI_KERNEL_BENCH(BM_FillVelocity);
EULERFSI_KERNEL_BENCH(BM_ScalarAdvectionRhs);
EULERFSI_KERNEL_BENCH(BM_TensorTransportRhs);
EULERFSI_KERNEL_BENCH(BM_AddElasticForce);

}  // namespace
