// The rigid sphere's correction (src/solid/rigid_model.hpp) on a sheared pipe flow, on 1 and 2 ranks:
//  - a free body: the blend changes neither the flow's momentum nor its angular momentum about the
//    centre (the fit is the psi-weighted least squares that conserves both; round-off), and the
//    velocity where psi = 1 is a rigid motion: every strain rate of the MAC stencil is zero there
//    (a rigid field u = U + w x r has du/dx = 0 and du/dy + dv/dx = 0 exactly on the grid);
//  - a fixed body: the velocity where psi = 1 is zero, and the momentum removed is its holding
//    impulse (the force times dt);
//  - a body held at its radius: the cross-section momentum is removed, x-momentum and the
//    angular momentum about the centre are kept.
// A fit that ignored the faces' first moments (a rotation about the centre while their psi-centroid
// is off it) left a free body a holding force of ~1e-4 in the particle_pipe_rigid regression case.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/flow_case.hpp"
#include "kernels/rigid_body.hpp"
#include "solver/rk3.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

CaseConfig rigid_case(SolidConstraint constraint) {
  CaseConfig cfg = test::small_case(Geometry::Pipe, 24, 24, 24, 1.0, 1.0, 1.0, 100.0, InitialFlow::Laminar);
  SolidConfig s;
  s.diameter = 0.45;  // 10.8 cells: psi = 1 on a core of radius 3.9 cells
  s.center = {0.5, 0.12, -0.05};
  s.model = SolidModelKind::Rigid;
  s.constraint = constraint;
  cfg.solids.push_back(s);
  return cfg;
}

// Momentum and angular momentum about c of the whole flow (owned faces), times dV.
struct Totals {
  double p[3] = {0, 0, 0}, l[3] = {0, 0, 0};
};

Totals totals(const test::CoupledCase& run, const double c[3]) {
  const Grid& g = run.grid;
  const Box b = g.interior();
  Totals t;
  for (int comp = 0; comp < 3; ++comp) {
    auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), run.flow.state().vel.c[comp]);
    for (int i = b.lo[0]; i < b.hi[0]; ++i)
      for (int j = b.lo[1]; j < b.hi[1]; ++j)
        for (int k = b.lo[2]; k < b.hi[2]; ++k) {
          const int ix[3] = {i, j, k};
          double r[3];
          for (int d = 0; d < 3; ++d) {
            r[d] = g.centre(d, ix[d]) + (d == comp ? 0.5 * g.h[d] : 0.0) - c[d];
            if (d == 0) r[d] -= g.length[0] * std::round(r[d] / g.length[0]);
          }
          double q[3];
          kernels::detail::lever(r, comp, q);
          t.p[comp] += u(i, j, k);
          for (int a = 0; a < 3; ++a) t.l[a] += q[a] * u(i, j, k);
        }
  }
  for (int a = 0; a < 3; ++a) {
    t.p[a] = run.comm.sum(t.p[a]) * g.cell_volume();
    t.l[a] = run.comm.sum(t.l[a]) * g.cell_volume();
  }
  return t;
}

// Largest strain rate of the MAC stencil over the cells whose faces it reads all have psi = 1, and
// the largest |u| there.
std::pair<double, double> strain_inside(const test::CoupledCase& run) {
  const Grid& g = run.grid;
  const auto& vel = run.flow.state().vel;
  auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), vel.c[0]);
  auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), vel.c[1]);
  auto w = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), vel.c[2]);
  const WindowField& body_psi = run.solids.bodies()[0].psi;
  auto psi_data = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), body_psi.data);
  const Box win = body_psi.window();
  auto psi = [&](int i, int j, int k) {  // psi on its window, 0 outside it
    const bool in = i >= win.lo[0] && i < win.hi[0] && j >= win.lo[1] && j < win.hi[1] && k >= win.lo[2] && k < win.hi[2];
    return in ? psi_data(i - win.lo[0], j - win.lo[1], k - win.lo[2]) : 0.0;
  };
  const Box b = g.interior();
  double strain = 0.0, speed = 0.0;
  for (int i = b.lo[0]; i < b.hi[0] - 1; ++i)
    for (int j = b.lo[1]; j < b.hi[1] - 2; ++j)
      for (int k = b.lo[2]; k < b.hi[2] - 2; ++k) {
        // every face the strains read has psi = 1 on both sides (cell i + 2 may be a ghost: psi is exact there)
        bool deep = true;
        for (int di = 0; di <= 2; ++di)
          for (int dj = 0; dj <= 2; ++dj)
            for (int dk = 0; dk <= 2; ++dk) deep = deep && psi(i + di, j + dj, k + dk) == 1.0;
        if (!deep) continue;
        const double e[6] = {u(i + 1, j, k) - u(i, j, k), v(i, j + 1, k) - v(i, j, k), w(i, j, k + 1) - w(i, j, k),
                             u(i, j + 1, k) - u(i, j, k) + v(i + 1, j, k) - v(i, j, k),
                             u(i, j, k + 1) - u(i, j, k) + w(i + 1, j, k) - w(i, j, k),
                             v(i, j, k + 1) - v(i, j, k) + w(i, j + 1, k) - w(i, j, k)};
        for (double x : e) strain = std::max(strain, std::fabs(x) / g.h[0]);
        speed = std::max({speed, std::fabs(u(i, j, k)), std::fabs(v(i, j, k)), std::fabs(w(i, j, k))});
      }
  return {run.comm.max(strain), run.comm.max(speed)};
}

}  // namespace

TEST(RigidBody, FreeBodyBecomesRigidAndKeepsMomentumAndAngularMomentum) {
  test::CoupledCase run(rigid_case(SolidConstraint::None));
  const double c[3] = {0.5, 0.12, -0.05};
  const Totals before = totals(run, c);
  const auto [strain0, speed0] = strain_inside(run);
  run.solids.constrain_velocity(run.flow.state().vel, 1e-3, 0);
  const Totals after = totals(run, c);
  const auto [strain, speed] = strain_inside(run);
  if (test::rank() == 0)
    std::printf("free: dP = (%.1e, %.1e, %.1e) of %.3f, dL = (%.1e, %.1e, %.1e); strain inside %.3f -> %.1e\n",
                after.p[0] - before.p[0], after.p[1] - before.p[1], after.p[2] - before.p[2], before.p[0],
                after.l[0] - before.l[0], after.l[1] - before.l[1], after.l[2] - before.l[2], strain0, strain);
  // sums of ~1e4 O(1) terms: round-off ~1e-13 of the flow's momentum
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(after.p[a], before.p[a], 1e-12 * std::fabs(before.p[0]));
    EXPECT_NEAR(after.l[a], before.l[a], 1e-12 * std::fabs(before.p[0]));
  }
  EXPECT_GT(strain0, 1.0);  // the laminar shear 4 r / R^2 ... is there before
  EXPECT_LT(strain, 1e-10 * speed / run.grid.h[0]);
}

TEST(RigidBody, FixedBodyStopsAndItsImpulseIsTheMomentumRemoved) {
  test::CoupledCase run(rigid_case(SolidConstraint::Fixed));
  const double c[3] = {0.5, 0.12, -0.05};
  const Totals before = totals(run, c);
  const double dt = 1e-3;
  for (int s = 0; s < Rk3::stages; ++s) run.solids.constrain_velocity(run.flow.state().vel, dt, s);
  const Totals after = totals(run, c);
  const auto [strain, speed] = strain_inside(run);
  const auto hold = run.solids.bodies()[0].model->holding_force();
  if (test::rank() == 0)
    std::printf("fixed: |u| inside %.1e; momentum removed (%.4e, %.4e, %.4e), holding impulse (%.4e, %.4e, %.4e)\n",
                speed, after.p[0] - before.p[0], after.p[1] - before.p[1], after.p[2] - before.p[2], hold[0] * dt,
                hold[1] * dt, hold[2] * dt);
  EXPECT_EQ(speed, 0.0);
  // the first substep removed it all; the next two had nothing left to remove
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(hold[a] * dt, after.p[a] - before.p[a], 1e-12 * std::fabs(before.p[0]));
  EXPECT_LT(hold[0], 0.0);  // the laminar flow carried the body downstream
}

TEST(RigidBody, RadialConstraintRemovesOnlyTheCrossSectionMotion) {
  test::CoupledCase run(rigid_case(SolidConstraint::Radial));
  const double c[3] = {0.5, 0.12, -0.05};
  const Totals before = totals(run, c);
  const double dt = 1e-3;
  for (int s = 0; s < Rk3::stages; ++s) run.solids.constrain_velocity(run.flow.state().vel, dt, s);
  const Totals after = totals(run, c);
  const auto hold = run.solids.bodies()[0].model->holding_force();
  EXPECT_NEAR(after.p[0], before.p[0], 1e-12 * std::fabs(before.p[0]));
  EXPECT_NEAR(hold[0], 0.0, 1e-12 * std::fabs(before.p[0]) / dt);
  for (int a = 1; a < 3; ++a) EXPECT_NEAR(hold[a] * dt, after.p[a] - before.p[a], 1e-12 * std::fabs(before.p[0]));
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(after.l[a], before.l[a], 1e-12 * std::fabs(before.p[0]));
}

// The diagnostics' spin (particle.csv spin_x/y/z) of a body whose velocity is a rigid motion is that
// motion's angular velocity, to round-off, for a soft body as for a rigid one.
TEST(RigidBody, DiagnosticsMeasureTheSpinOfARigidMotion) {
  for (SolidModelKind model : {SolidModelKind::Rigid, SolidModelKind::ReferenceMap}) {
    CaseConfig cfg = rigid_case(SolidConstraint::None);
    cfg.solids[0].model = model;
    test::CoupledCase run(cfg);
    const double U[3] = {0.3, -0.1, 0.05}, w[3] = {0.7, -1.1, 2.3};
    const ParticleState before = run.particle();
    const double c[3] = {before.centre[0], before.centre[1], before.centre[2]};
    const Grid& g = run.grid;
    for (int comp = 0; comp < 3; ++comp) {
      auto u = Kokkos::create_mirror_view(run.flow.state().vel.c[comp]);
      for (int i = 0; i < g.ext(0); ++i)
        for (int j = 0; j < g.ext(1); ++j)
          for (int k = 0; k < g.ext(2); ++k) {
            const int ix[3] = {i, j, k};
            double r[3];
            for (int d = 0; d < 3; ++d) r[d] = g.centre(d, ix[d]) + (d == comp ? 0.5 * g.h[d] : 0.0) - c[d];
            const double wxr[3] = {w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0]};
            u(i, j, k) = U[comp] + wxr[comp];
          }
      Kokkos::deep_copy(run.flow.state().vel.c[comp], u);
    }
    const ParticleState s = run.particle();
    if (test::rank() == 0)
      std::printf("%s: spin (%.15f, %.15f, %.15f)\n", to_string(model), s.spin[0], s.spin[1], s.spin[2]);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(s.spin[a], w[a], 1e-11);
  }
}

// With a rigid body the step keeps the explicit viscous limit on mu_f even where the viscosity is
// implicit (src/solver/flow_solver.cpp, stable_dt: beyond it the rigid correction's splitting error
// grows with mu dt / h^2; docs/VALIDATION.md); without one, implicit viscosity lifts it.
TEST(RigidBody, KeepsTheExplicitViscousLimitWithImplicitViscosity) {
#ifndef EULERFSI_HAVE_MPI
  GTEST_SKIP() << "time.implicit_viscosity needs an MPI build";
#endif
  CaseConfig cfg = rigid_case(SolidConstraint::None);
  cfg.flow.Re = 1.0;
  cfg.time.implicit_viscosity = true;
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  double inv_h2 = 0.0;
  for (int d = 0; d < 3; ++d) inv_h2 += 1.0 / (grid.h[d] * grid.h[d]);
  const double explicit_limit = 1.65 / (4.0 * 1.0 * inv_h2);
  test::CoupledCase rigid(cfg);
  EXPECT_LE(rigid.flow.stable_dt(), explicit_limit * (1.0 + 1e-12));
  cfg.solids[0].model = SolidModelKind::ReferenceMap;
  cfg.solids[0].We = 1e6;  // no elastic wave limit
  test::CoupledCase soft(cfg);
  EXPECT_GT(soft.flow.stable_dt(), 2.0 * explicit_limit);
}

// The diagnostics read psi and B up to kGhost + 1 cells around a body's active box (the force
// terms' stencils): the window that stores them must hold that reach wherever the body is, next to
// the wall included (a window one cell wider than psi let a free sphere near the wall read outside
// its allocation). The same holds for the reference map's window.
TEST(RigidBody, WindowHoldsTheStencilReachAroundTheBody) {
  for (SolidModelKind model : {SolidModelKind::Rigid, SolidModelKind::ReferenceMap}) {
    for (double y : {0.0, 0.2, 0.26}) {  // a = 0.225: 0.26 leaves a gap of 0.015 (0.4 h) to the wall
      CaseConfig cfg = rigid_case(SolidConstraint::None);
      cfg.solids[0].model = model;
      cfg.solids[0].center = {0.5, y, 0.0};
      test::CoupledCase run(cfg);
      const SolidBody& body = run.solids.bodies()[0];
      const Box active = body.model->active_box();
      if (active.empty()) continue;  // not on this rank
      const Box need = active.grown(kGhost + 1, run.grid.all()), have = body.psi.window();
      for (int d = 0; d < 3; ++d) {
        EXPECT_LE(have.lo[d], need.lo[d]) << to_string(model) << " at y = " << y << ", direction " << d;
        EXPECT_GE(have.hi[d], need.hi[d]) << to_string(model) << " at y = " << y << ", direction " << d;
      }
    }
  }
}
