// time.implicit_viscosity: mu_f by Crank-Nicolson within each RK3 substep (a Helmholtz solve per
// component), at time steps far beyond the explicit viscous limit dt_v = 1.65 / (4 mu sum 1/h^2).
//  - Taylor-Green (periodic, Re = 1): a mode of wavenumber k decays per substep by the
//    Crank-Nicolson factor (1 - a/2) / (1 + a/2), a = alpha dt nu k_h^2 (k_h^2 the 7-point
//    Laplacian's eigenvalue): the kinetic energy after N steps is the product of those factors,
//    squared. The explicit run decays at exp(-2 nu k_h^2 t) up to RK3's error; both are checked.
//  - Couette (walls moving at -1 and +1, Re = 1, from rest): the wall velocities enter the
//    implicit half's right-hand side; the steady profile is linear, which the 7-point Laplacian
//    with the ghost rule u(-1) = 2 u_wall - u(0) holds exactly.
//  - Pipe (interpolated wall, Re = 1, from rest): the wall's direct forcing in the right-hand
//    side and the mean pressure gradient carried from the last step leave the steady state of
//    the discrete equations untouched: dp/dx equals the explicit run's to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

double explicit_viscous_dt(const Grid& g, double mu) {
  double inv_h2 = 0.0;
  for (int d = 0; d < 3; ++d) inv_h2 += 1.0 / (g.h[d] * g.h[d]);
  return 1.65 / (4.0 * mu * inv_h2);
}

// Steps of fixed size dt to t_end (the last one shortened).
void run_fixed(FlowSolver& flow, double dt, double t_end) {
  double t = 0.0;
  while (t < t_end * (1.0 - 1e-14)) {
    const double step = std::min(dt, t_end - t);
    flow.advance(t, step, nullptr);
    t += step;
  }
}

}  // namespace

// A build without MPI has no FFTW-MPI transforms: the key is refused there (test_config).
#ifdef EULERFSI_HAVE_MPI
#define EULERFSI_NEEDS_MPI()
#else
#define EULERFSI_NEEDS_MPI() GTEST_SKIP() << "time.implicit_viscosity needs an MPI build"
#endif

TEST(ImplicitViscosity, TaylorGreenDecaysAtTheCrankNicolsonRate) {
  EULERFSI_NEEDS_MPI();
  const int n = 16;
  const double re = 1.0, nu = 1.0 / re;
  CaseConfig cfg = test::small_case(Geometry::Periodic, n, n, 4, 1.0, 1.0, 4.0 / n, re, InitialFlow::TaylorGreen);
  cfg.time.implicit_viscosity = true;
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  FlowSolver flow(cfg, grid, comm);
  flow.set_initial_condition();
  // u = sin(2 pi x) cos(2 pi y): k_h^2 = 2 (4/h^2) sin^2(pi h)
  const double h = 1.0 / n, s = std::sin(M_PI * h);
  const double kh2 = 2.0 * 4.0 * s * s / (h * h);
  const double dt = 5.0 * explicit_viscous_dt(grid, nu);  // nu k_h^2 dt = 0.21
  const int steps = 40;
  const double ke0 = flow.diagnostics(0.0).kinetic_energy;
  run_fixed(flow, dt, steps * dt);
  const double ke = flow.diagnostics(0.0).kinetic_energy;
  double g = 1.0;
  for (int st = 0; st < Rk3::stages; ++st) {
    const double a = Rk3::alpha(st) * dt * nu * kh2;
    g *= (1.0 - 0.5 * a) / (1.0 + 0.5 * a);
  }
  const double predicted = std::pow(g, 2 * steps), exact = std::exp(-2.0 * nu * kh2 * steps * dt);
  if (test::rank() == 0)
    std::printf("Taylor-Green at 5 explicit limits, %d steps: KE ratio %.10e, Crank-Nicolson %.10e, exact %.10e\n",
                steps, ke / ke0, predicted, exact);
  // the mode is an eigenvector of the linear scheme; the advection of Taylor-Green is a pure
  // gradient up to O(h^2 u^2 / nu) (Re = 1: ~1e-4 of the decay), so the prediction holds to 1e-3
  EXPECT_NEAR(ke / ke0, predicted, 1e-3 * predicted);
  // and the time error of Crank-Nicolson at this step is visible: (nu k^2 dt)^2 sum alpha^3 / 12
  // = 7e-4 of the rate, 1.2 % of the energy over these 40 steps; the test must be able to see it
  EXPECT_GT(std::fabs(predicted / exact - 1.0), 5e-3);
}

TEST(ImplicitViscosity, CouetteReachesTheLinearProfile) {
  EULERFSI_NEEDS_MPI();
  CaseConfig cfg = test::small_case(Geometry::Couette, 4, 16, 4, 0.25, 1.0, 0.25, 1.0, InitialFlow::Rest);
  cfg.flow.wall_velocity = {-1.0, 1.0};
  cfg.time.implicit_viscosity = true;
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  FlowSolver flow(cfg, grid, comm);
  flow.set_initial_condition();
  // the slowest mode decays as exp(-pi^2 t): 1e-13 at t = 3
  run_fixed(flow, 20.0 * explicit_viscous_dt(grid, 1.0), 3.0);
  auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), flow.state().vel.c[0]);
  const Box box = grid.interior();
  double err = 0.0;
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int k = box.lo[2]; k < box.hi[2]; ++k) {
        const double y = grid.domain_lo(1) + (j - kGhost + 0.5) * grid.h[1];
        err = std::max(err, std::fabs(u(i, j, k) - 2.0 * y));
      }
  err = comm.max(err);
  if (test::rank() == 0) std::printf("Couette at 20 explicit limits: max |u - u_exact| = %.2e\n", err);
  EXPECT_LT(err, 1e-9);
}

TEST(ImplicitViscosity, PipeKeepsTheSteadyStateOfTheExplicitScheme) {
  EULERFSI_NEEDS_MPI();
  double dpdx[2];
  for (int implicit = 0; implicit < 2; ++implicit) {
    CaseConfig cfg = test::small_case(Geometry::Pipe, 4, 24, 24, 1.0 / 6.0, 1.0, 1.0, 1.0, InitialFlow::Rest);
    cfg.time.implicit_viscosity = implicit == 1;
    const Comm comm;
    const Grid grid = make_grid(cfg, comm);
    FlowSolver flow(cfg, grid, comm);
    flow.set_initial_condition();
    // slowest mode exp(-(2.405 / R)^2 t): 1e-10 at t = 1; the implicit step is CFL 0.2 on u = 2,
    // about 20 explicit limits
    test::run_flow(flow, 1.0);
    dpdx[implicit] = flow.dpdx();
  }
  if (test::rank() == 0)
    std::printf("pipe steady dp/dx: explicit %.12f, implicit %.12f (exact -32)\n", dpdx[0], dpdx[1]);
  EXPECT_NEAR(dpdx[1], dpdx[0], 1e-8 * std::fabs(dpdx[0]));
}
