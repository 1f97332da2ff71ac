// Laminar flow at constant flow rate to steady state, against the exact solutions:
//  - square duct (walls on the grid lines): dp/dx -> -28.454/Re (Darcy f Re = 56.91) and the
//    series solution; the ghost-cell no-slip and central differences are second order, so the
//    errors fall by ~4 when h halves (accepted: > 3);
//  - penalized pipe, dp/dx -> -32/Re, u = 2(1 - 4 r^2), with each wall of flow.pipe_wall:
//    "sharp" (the paper's mask): the wall is a staircase of cells, a first-order error, so the
//    errors must fall under refinement (accepted: ratio > 1.5 for h/2). Bound: the staircase puts
//    the wall within h/2 of r = R; at fixed flow rate dp/dx ~ R^-4 and u_max ~ R^-2, so both
//    relative errors stay below 4 (h/2) / R = 4 h.
//    "interpolated" (the default): second order. The convergence study (DISABLED_ test below,
//    from the laminar profile to t = 0.3, Re = 1) measured
//        cells across          24          48          96
//        dp/dx error       1.432e-2    3.556e-3    8.342e-4   (ratios 4.03, 4.26)
//        velocity error    9.028e-3    2.637e-3    6.407e-4   (ratios 3.42, 4.12)
//    and for the sharp mask dp/dx 6.74e-2, 3.83e-2, 2.28e-2 (order 0.8). The test runs 24 and 48:
//    ratios in [3, 5] (second order, room for the h^3 remainder of the forced layer) and both
//    errors at 48 cells below 5e-3 (1.4x and 1.9x the measured values; the target was 1%).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "solver/exact_solutions.hpp"
#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

struct SteadyErrors {
  double dpdx_rel = 0.0;      // |dp/dx - exact| / |exact|
  double velocity_rel = 0.0;  // max |u - exact| / max exact
};

// From rest to t_end = 1.2 by default: the slowest viscous mode decays like exp(-2 pi^2 t / Re)
// (duct) or faster (pipe): that leaves < 1e-10. From the laminar profile the start is already
// within the discretisation error of the steady state, so a shorter t_end suffices.
SteadyErrors steady_errors(Geometry geo, int n, PipeWall wall = PipeWall::Sharp, InitialFlow init = InitialFlow::Rest,
                           double t_end = 1.2) {
  const double re = 1.0;
  CaseConfig cfg = test::small_case(geo, 4, n, n, 4.0 / n, 1.0, 1.0, re, init);
  cfg.flow.pipe_wall = wall;
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  FlowSolver flow(cfg, grid, comm);
  flow.set_initial_condition();
  test::run_flow(flow, t_end);
  const double mu = 1.0 / re;
  const bool pipe = geo == Geometry::Pipe;
  const double dpdx_exact = pipe ? exact::pipe_dpdx(mu, 1.0) : exact::duct_dpdx(1.0, 1.0, mu, 1.0);
  auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), flow.state().u());
  const Box b = grid.interior();
  double err = 0.0, umax = 0.0;
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) {
        const double y = grid.centre(1, j), z = grid.centre(2, k);
        const double ue = pipe ? exact::pipe_velocity(y, z, 1.0) : exact::duct_velocity(y, z, 1.0, 1.0, mu, 1.0);
        err = std::max(err, std::fabs(u(i, j, k) - ue));
        umax = std::max(umax, ue);
      }
  SteadyErrors e;
  e.dpdx_rel = std::fabs(flow.dpdx() - dpdx_exact) / std::fabs(dpdx_exact);
  e.velocity_rel = comm.max(err) / comm.max(umax);
  return e;
}

}  // namespace

TEST(LaminarDuct, PressureGradientAndProfileConvergeAtSecondOrder) {
  const SteadyErrors c = steady_errors(Geometry::Duct, 16);
  const SteadyErrors f = steady_errors(Geometry::Duct, 32);
  if (test::rank() == 0)
    std::printf("duct: dp/dx error %.3e -> %.3e (ratio %.2f), velocity error %.3e -> %.3e (ratio %.2f)\n", c.dpdx_rel,
                f.dpdx_rel, c.dpdx_rel / f.dpdx_rel, c.velocity_rel, f.velocity_rel, c.velocity_rel / f.velocity_rel);
  // second order: ratio 4 when h halves; [3, 5] leaves room for the O(h^4) remainder
  EXPECT_GT(c.dpdx_rel / f.dpdx_rel, 3.0);
  EXPECT_LT(c.dpdx_rel / f.dpdx_rel, 5.0);
  EXPECT_GT(c.velocity_rel / f.velocity_rel, 3.0);
  EXPECT_LT(c.velocity_rel / f.velocity_rel, 5.0);
}

TEST(LaminarPipe, SharpMaskConvergesUnderRefinement) {
  const SteadyErrors c = steady_errors(Geometry::Pipe, 16);
  const SteadyErrors f = steady_errors(Geometry::Pipe, 32);
  if (test::rank() == 0)
    std::printf("pipe: dp/dx error %.3e -> %.3e (ratio %.2f), velocity error %.3e -> %.3e (ratio %.2f)\n", c.dpdx_rel,
                f.dpdx_rel, c.dpdx_rel / f.dpdx_rel, c.velocity_rel, f.velocity_rel, c.velocity_rel / f.velocity_rel);
  EXPECT_LT(c.dpdx_rel, 4.0 / 16);
  EXPECT_LT(f.dpdx_rel, 4.0 / 32);
  EXPECT_GT(c.dpdx_rel / f.dpdx_rel, 1.5);
  EXPECT_LT(c.velocity_rel, 4.0 / 16);
  EXPECT_LT(f.velocity_rel, 4.0 / 32);
  EXPECT_GT(c.velocity_rel / f.velocity_rel, 1.5);
}

TEST(LaminarPipe, InterpolatedWallConvergesAtSecondOrder) {
  const SteadyErrors c = steady_errors(Geometry::Pipe, 24, PipeWall::Interpolated, InitialFlow::Laminar, 0.3);
  const SteadyErrors f = steady_errors(Geometry::Pipe, 48, PipeWall::Interpolated, InitialFlow::Laminar, 0.3);
  if (test::rank() == 0)
    std::printf("pipe (interpolated wall): dp/dx error %.3e -> %.3e (ratio %.2f), velocity error %.3e -> %.3e "
                "(ratio %.2f)\n",
                c.dpdx_rel, f.dpdx_rel, c.dpdx_rel / f.dpdx_rel, c.velocity_rel, f.velocity_rel,
                c.velocity_rel / f.velocity_rel);
  EXPECT_GT(c.dpdx_rel / f.dpdx_rel, 3.0);
  EXPECT_LT(c.dpdx_rel / f.dpdx_rel, 5.0);
  EXPECT_GT(c.velocity_rel / f.velocity_rel, 3.0);
  EXPECT_LT(c.velocity_rel / f.velocity_rel, 5.0);
  EXPECT_LT(f.dpdx_rel, 5e-3);
  EXPECT_LT(f.velocity_rel, 5e-3);
}

// The convergence study behind the tolerances above (minutes at 96 cells; run by hand with
// --gtest_also_run_disabled_tests, EULERFSI_STUDY_N="24 48 96" picks the resolutions).
TEST(LaminarPipe, DISABLED_WallConvergenceStudy) {
  const char* env = std::getenv("EULERFSI_STUDY_N");
  std::istringstream ns(env ? env : "24 48 96");
  const double t_end = std::getenv("EULERFSI_STUDY_T") ? std::atof(std::getenv("EULERFSI_STUDY_T")) : 0.3;
  for (int n; ns >> n;)
    for (PipeWall wall : {PipeWall::Sharp, PipeWall::Interpolated}) {
      const SteadyErrors e = steady_errors(Geometry::Pipe, n, wall, InitialFlow::Laminar, t_end);
      if (test::rank() == 0)
        std::printf("pipe %-12s n = %3d: dp/dx error %.4e, velocity error %.4e\n", to_string(wall), n, e.dpdx_rel,
                    e.velocity_rel);
    }
}
