// Taylor-Green vortex in a periodic box: the kinetic energy decays as exp(-2 nu k^2 t) with
// k^2 = kx^2 + ky^2. The 2nd-order Laplacian replaces k^2 by (4/h^2) sin^2(k h/2), a relative
// error (kh)^2/12 - (kh)^4/360: 1.278e-2 on 16^2 and 3.209e-3 on 32^2, ratio 3.98.
#include <gtest/gtest.h>

#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

double decay_rate_error(int n) {
  const double re = 100.0, t_end = 0.25;
  CaseConfig cfg = test::small_case(Geometry::Periodic, n, n, 4, 1.0, 1.0, 4.0 / n, re, InitialFlow::TaylorGreen);
  cfg.time.cfl = 0.1;
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  FlowSolver flow(cfg, grid, comm);
  flow.set_initial_condition();
  const double ke0 = flow.diagnostics(0.0).kinetic_energy;
  test::run_flow(flow, t_end);
  const double ke1 = flow.diagnostics(0.0).kinetic_energy;
  const double k2 = 2.0 * std::pow(2.0 * M_PI, 2);
  const double exact = 2.0 * k2 / re;
  const double measured = -std::log(ke1 / ke0) / t_end;
  return std::fabs(measured - exact) / exact;
}

}  // namespace

TEST(TaylorGreen, DecayRateConvergesAtSecondOrder) {
  const double e16 = decay_rate_error(16);
  const double e32 = decay_rate_error(32);
  if (eulerfsi::test::rank() == 0) std::printf("decay-rate error: N=16 %.4e  N=32 %.4e  ratio %.3f\n", e16, e32, e16 / e32);
  // the Laplacian's own error, from the expansion above, within 10% (advection and time errors are smaller)
  EXPECT_NEAR(e16, 1.278e-2, 0.1 * 1.278e-2);
  EXPECT_NEAR(e32, 3.209e-3, 0.1 * 3.209e-3);
  // second order: ratio 4 up to the O(h^4) term (3.98 predicted)
  EXPECT_GT(e16 / e32, 3.6);
  EXPECT_LT(e16 / e32, 4.4);
}
