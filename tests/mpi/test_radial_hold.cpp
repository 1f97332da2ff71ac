// A soft body held at its (y, z) (solid.constraint = "radial", src/solid/radial_hold.hpp), on 1 and
// 2 ranks:
//  - one step's correction is a uniform acceleration over the body, u_D += psi_D V_D: the x-velocity
//    untouched, the change in y and z proportional to psi (zero outside the body, the deformation
//    kept), the body's psi-weighted cross-stream momentum set to its target (round-off), and the
//    momentum added is the holding impulse (the force times dt);
//  - over 40 steps of a laminar pipe flow at Re = 100 the centroid stays at its place while the
//    body deforms and moves along x with the flow; the free body drifts, the held one does not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solid/radial_hold.hpp"
#include "solver/rk3.hpp"
#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

CaseConfig soft_case(SolidConstraint constraint) {
  CaseConfig cfg = test::small_case(Geometry::Pipe, 24, 24, 24, 1.0, 1.0, 1.0, 100.0, InitialFlow::Laminar);
  SolidConfig s;
  s.diameter = 0.4;
  s.center = {0.5, 0.2, 0.0};
  s.We = 0.5;
  s.model = SolidModelKind::ReferenceMap;
  s.constraint = constraint;
  cfg.solids.push_back(s);
  return cfg;
}

// Host copies of the three velocity components.
struct HostVelocity {
  Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace> c[3];
  explicit HostVelocity(const test::CoupledCase& run) {
    for (int d = 0; d < 3; ++d) {
      c[d] = Kokkos::create_mirror(run.flow.state().vel.c[d]);  // a copy, never the device's own view
      Kokkos::deep_copy(c[d], run.flow.state().vel.c[d]);
    }
  }
};

// (y, z) of the psi-weighted centroid of solid 0's cells, the centroid the hold keeps.
std::pair<double, double> psi_centroid(const test::CoupledCase& run) {
  const Grid& g = run.grid;
  const WindowField& psi = run.solids.bodies()[0].psi;
  auto p = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), psi.data);
  const Box b = intersection(psi.window(), g.interior());
  double m[3] = {0, 0, 0};
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) {
        const double v = p(i - psi.lo[0], j - psi.lo[1], k - psi.lo[2]);
        m[0] += v;
        m[1] += v * g.centre(1, j);
        m[2] += v * g.centre(2, k);
      }
  for (double& x : m) x = run.comm.sum(x);
  return {m[1] / m[0], m[2] / m[0]};
}

constexpr int kSteps = 80;

}  // namespace

TEST(RadialHold, OneStepIsAUniformAccelerationOverTheBody) {
  test::CoupledCase run(soft_case(SolidConstraint::Radial));
  const Grid& g = run.grid;
  const HostVelocity before(run);
  const double dt = 1e-3;
  for (int s = 0; s < Rk3::stages; ++s) run.solids.constrain_velocity(run.flow.state().vel, dt, s);
  const HostVelocity after(run);
  const SolidBody& body = run.solids.bodies()[0];
  auto psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), body.psi.data);
  const Box w = body.psi.window(), b = g.interior();
  auto psi_at = [&](int i, int j, int k) {
    const bool in = i >= w.lo[0] && i < w.hi[0] && j >= w.lo[1] && j < w.hi[1] && k >= w.lo[2] && k < w.hi[2];
    return in ? psi(i - w.lo[0], j - w.lo[1], k - w.lo[2]) : 0.0;
  };
  // u_D(after) - u_D(before) = psi_D V_D with one V_D per component (the sum of the substeps')
  double dx_max = 0.0, ratio_lo[2] = {1e300, 1e300}, ratio_hi[2] = {-1e300, -1e300}, outside = 0.0;
  double added[2] = {0.0, 0.0}, psi_mom[2] = {0.0, 0.0}, mass[2] = {0.0, 0.0}, offset[2] = {0.0, 0.0};
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) {
        dx_max = std::max(dx_max, std::fabs(after.c[0](i, j, k) - before.c[0](i, j, k)));
        for (int d = 0; d < 2; ++d) {
          const double p = 0.5 * (psi_at(i, j, k) + psi_at(i, j + (d == 0), k + (d == 1)));
          const double du = after.c[d + 1](i, j, k) - before.c[d + 1](i, j, k);
          added[d] += du;
          psi_mom[d] += p * after.c[d + 1](i, j, k);
          mass[d] += p;
          offset[d] += p * (g.centre(d + 1, d == 0 ? j : k) + 0.5 * g.h[d + 1] - body.cfg.center[d + 1]);
          if (p > 1e-3) {
            ratio_lo[d] = std::min(ratio_lo[d], du / p);
            ratio_hi[d] = std::max(ratio_hi[d], du / p);
          } else if (p == 0.0) {
            outside = std::max(outside, std::fabs(du));
          }
        }
      }
  const double dv = g.cell_volume();
  const auto hold = holding_force(body);
  for (int d = 0; d < 2; ++d) {
    added[d] = run.comm.sum(added[d]) * dv;
    psi_mom[d] = run.comm.sum(psi_mom[d]) * dv;
    mass[d] = run.comm.sum(mass[d]) * dv;
    offset[d] = run.comm.sum(offset[d]) * dv;
    ratio_lo[d] = -run.comm.max(-ratio_lo[d]);
    ratio_hi[d] = run.comm.max(ratio_hi[d]);
  }
  dx_max = run.comm.max(dx_max);
  outside = run.comm.max(outside);
  if (test::rank() == 0)
    std::printf("V = (%.6e .. %.6e, %.6e .. %.6e); impulse (%.4e, %.4e), hold*dt (%.4e, %.4e)\n", ratio_lo[0],
                ratio_hi[0], ratio_lo[1], ratio_hi[1], added[0], added[1], hold[1] * dt, hold[2] * dt);
  EXPECT_EQ(dx_max, 0.0);
  EXPECT_EQ(outside, 0.0);
  const double scale = 1.0;  // the laminar velocity's scale: round-off is relative to it
  for (int d = 0; d < 2; ++d) {
    EXPECT_NEAR(ratio_lo[d], ratio_hi[d], 1e-12 * scale);  // one V over the whole body
    EXPECT_NEAR(hold[d + 1] * dt, added[d], 1e-12 * scale * mass[d]);
    // the last substep left the momentum that brings the offset back over tau = 10 steps (the
    // integral of the offset is still zero: it starts with the step's end)
    EXPECT_NEAR(psi_mom[d], -2.0 * offset[d] / (10.0 * dt), 1e-10 * scale * mass[d]);
  }
  EXPECT_EQ(hold[0], 0.0);
}

TEST(RadialHold, KeepsTheCentroidWhileTheFreeBodyDrifts) {
  double drift[2] = {0, 0}, moved_x[2] = {0, 0}, deformation[2] = {0, 0};
  for (int held = 0; held < 2; ++held) {
    test::CoupledCase run(soft_case(held ? SolidConstraint::Radial : SolidConstraint::None));
    const ParticleState start = run.particle();
    double t = 0.0;
    for (int n = 0; n < kSteps; ++n) {
      const double dt = run.flow.stable_dt(run.solids.max_wave_speed());
      run.flow.advance(t, dt, &run.solids);
      t += dt;
      const double* c = run.solids.bodies()[0].cfg.center.data();
      const auto [y, z] = psi_centroid(run);
      drift[held] = std::max(drift[held], std::hypot(y - c[1], z - c[2]));
      if (test::rank() == 0 && n % 10 == 9) std::printf("%s step %d: offset (%.3e, %.3e)\n", held ? "held" : "free", n + 1, y - c[1], z - c[2]);
    }
    const ParticleState s = run.particle();
    moved_x[held] = s.centre[0] - start.centre[0];
    deformation[held] = s.taylor_D;
  }
  if (test::rank() == 0)
    std::printf("free: drift %.3e, moved %.4f along x, D %.4f; held: drift %.3e, moved %.4f, D %.4f\n", drift[0],
                moved_x[0], deformation[0], drift[1], moved_x[1], deformation[1]);
  const double h = 1.0 / 24.0;
  EXPECT_GT(drift[0], 0.02 * h);        // the free body migrates ...
  EXPECT_LT(drift[1], 0.1 * drift[0]);  // ... the held one keeps its place
  EXPECT_GT(moved_x[1], 0.5 * moved_x[0]);  // free along x
  EXPECT_GT(deformation[1], 0.5 * deformation[0]);  // and free to deform
}
