#pragma once
// Builds small in-memory cases and runs the flow solver on them, for validation tests.
#include <algorithm>
#include <cmath>
#include <functional>

#include "app/simulation.hpp"
#include "config/case_config.hpp"
#include "parallel/comm.hpp"
#include "solid/particle_diagnostics.hpp"
#include "solid/solid_phase.hpp"
#include "solver/flow_solver.hpp"

namespace eulerfsi::test {

inline CaseConfig small_case(Geometry geo, int nx, int ny, int nz, double lx, double ly, double lz, double re,
                             InitialFlow init) {
  CaseConfig cfg;
  cfg.source = "<test>";
  cfg.domain.geometry = geo;
  cfg.domain.cells = {nx, ny, nz};
  cfg.domain.length = {lx, ly, lz};
  cfg.flow.Re = re;
  cfg.flow.initial = init;
  return cfg;
}

// A case with bodies, set up as a run starts (initial flow, shapes with B = I, bodies at rest
// stopped, one projection).
struct CoupledCase {
  Comm comm;
  Grid grid;
  FlowSolver flow;
  SolidPhase solids;
  ParticleTracker tracker;
  explicit CoupledCase(const CaseConfig& cfg)
      : grid(make_grid(cfg, comm)), flow(cfg, grid, comm), solids(cfg, grid, flow.boundaries(), comm),
        tracker(cfg, grid, comm) {
    set_initial_state(flow, solids);
  }
  ParticleState particle() { return tracker.measure(solids, flow.state())[0]; }
  // The grid takes solid 0's mean x-velocity at time t, as the run loop does for
  // flow.frame_velocity = "particle".
  void follow_particle(double t) {
    flow.set_frame_velocity(tracker.mean_x_velocity(solids, flow.state(), 0, flow.frame_velocity()), t);
  }
};

// max |u|, |v|, |w| over the owned cells of every rank.
inline double max_abs_velocity(const CoupledCase& run) {
  const Box box = run.grid.interior();
  double m = 0.0;
  for (int c = 0; c < 3; ++c) {
    auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), run.flow.state().vel.c[c]);
    for (int i = box.lo[0]; i < box.hi[0]; ++i)
      for (int j = box.lo[1]; j < box.hi[1]; ++j)
        for (int k = box.lo[2]; k < box.hi[2]; ++k) m = std::max(m, std::fabs(u(i, j, k)));
  }
  return run.comm.max(m);
}

// Advances the flow (and the bodies, if given) to t_end with the stable step; calls `each` after
// every step.
inline void run_flow(FlowSolver& flow, double t_end, const std::function<void(double t)>& each = {},
                     SolidPhase* solids = nullptr) {
  double t = 0.0;
  while (t < t_end * (1.0 - 1e-14)) {
    double dt = flow.stable_dt(solids ? solids->max_wave_speed() : 0.0);
    if (t + dt > t_end) dt = t_end - t;
    flow.advance(t, dt, solids);
    t += dt;
    if (each) each(t);
  }
}

}  // namespace eulerfsi::test
