// Laminar flow at constant flow rate from rest to steady state, against the exact solutions:
//  - square duct (walls on the grid lines): dp/dx -> -28.454/Re (Darcy f Re = 56.91) and the
//    series solution; the ghost-cell no-slip and central differences are second order, so the
//    errors fall by ~4 when h halves (accepted: > 3);
//  - penalized pipe: dp/dx -> -32/Re, u = 2(1 - 4 r^2); the wall is a staircase of cells, a
//    first-order error, so the errors must fall under refinement (accepted: ratio > 1.5 for h/2).
//    Bound: the staircase puts the wall within h/2 of r = R; at fixed flow rate dp/dx ~ R^-4 and
//    u_max ~ R^-2, so both relative errors stay below 4 (h/2) / R = 4 h.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/exact_solutions.hpp"
#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

struct SteadyErrors {
  double dpdx_rel = 0.0;      // |dp/dx - exact| / |exact|
  double velocity_rel = 0.0;  // max |u - exact| / max exact
};

SteadyErrors steady_errors(Geometry geo, int n) {
  const double re = 1.0;
  CaseConfig cfg = test::small_case(geo, 4, n, n, 4.0 / n, 1.0, 1.0, re, InitialFlow::Rest);
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  FlowSolver flow(cfg, grid, comm);
  flow.set_initial_condition();
  // slowest viscous mode decays like exp(-2 pi^2 t / Re) (duct) or faster (pipe): t = 1.2 leaves < 1e-10
  test::run_flow(flow, 1.2);
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

TEST(LaminarPipe, PenalizedPipeConvergesUnderRefinement) {
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
