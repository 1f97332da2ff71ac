// The grid may move along x with a velocity U (flow.frame_velocity): the state then holds
// u - U, the walls move with -U relative to the grid, the flow rate is U_b - U, and every output
// adds U back. For a flow that does not depend on x (laminar start in a pipe, duct or channel)
// the discrete operators see only differences of u in y and z, so the laboratory's flow must be
// the same in both frames to round-off: a wrong wall velocity, penalization target or flow-rate
// target shows up as an O(U) difference within one step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

// Max over the owned x-faces of |a - (b + shift)|, and max |a|.
std::pair<double, double> max_difference(const Field3& a, const Field3& b, double shift, const Box& box) {
  auto ha = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), a);
  auto hb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b);
  double diff = 0.0, scale = 0.0;
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int k = box.lo[2]; k < box.hi[2]; ++k) {
        diff = std::max(diff, std::fabs(ha(i, j, k) - (hb(i, j, k) + shift)));
        scale = std::max(scale, std::fabs(ha(i, j, k)));
      }
  return {diff, scale};
}

void compare_frames(Geometry geo, double u_frame) {
  // Re = 20 with a start from rest: the profile changes by O(1) over the run, through the walls
  CaseConfig cfg = test::small_case(geo, 8, 16, 16, 1.0, 1.0, 1.0, 20.0, InitialFlow::Rest);
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  FlowSolver lab(cfg, grid, comm), moving(cfg, grid, comm);
  lab.set_initial_condition();
  moving.set_initial_condition();
  moving.set_frame_velocity(u_frame, 0.0);
  // the same step in both frames (the CFL limit sees u - U)
  const double dt = std::min(lab.stable_dt(), moving.stable_dt());
  double t = 0.0, worst_dpdx = 0.0;
  for (int step = 0; step < 30; ++step) {
    lab.advance(t, dt);
    moving.advance(t, dt);
    t += dt;
    worst_dpdx = std::max(worst_dpdx, std::fabs(lab.dpdx() - moving.dpdx()) / std::fabs(lab.dpdx()));
  }
  const Box box = grid.interior();
  double diff = 0.0, scale = 0.0;
  for (int c = 0; c < 3; ++c) {
    const auto [d, s] = max_difference(lab.state().vel.c[c], moving.state().vel.c[c], c == 0 ? u_frame : 0.0, box);
    diff = std::max(diff, d);
    scale = std::max(scale, s);
  }
  diff = comm.max(diff);
  scale = comm.max(scale);
  const FlowDiagnostics a = lab.diagnostics(dt), b = moving.diagnostics(dt);
  if (test::rank() == 0)
    std::printf("%s, U = %.2f, t = %.4f: max |u_lab - (u + U)| = %.2e (max |u| %.3f), dp/dx %.6f vs %.6f (worst rel. "
                "%.1e), bulk %.15f vs %.15f, KE %.10f vs %.10f, frame moved %.6f\n",
                to_string(geo), u_frame, t, diff, scale, a.dpdx, b.dpdx, worst_dpdx, a.bulk_u, b.bulk_u,
                a.kinetic_energy, b.kinetic_energy, moving.frame_offset());
  // round-off: ~30 steps x 3 substeps of O(1) sums, each losing ~1e-16 U; 1e-11 leaves a margin of
  // 100 and is 1e-10 of the O(U) error a wrong wall velocity makes
  EXPECT_LT(diff, 1e-11 * (scale + std::fabs(u_frame)));
  EXPECT_LT(worst_dpdx, 1e-10);
  EXPECT_NEAR(b.bulk_u, a.bulk_u, 1e-12);
  EXPECT_NEAR(b.kinetic_energy, a.kinetic_energy, 1e-11);
  EXPECT_NEAR(moving.frame_offset(), u_frame * t, 1e-14 * std::fabs(u_frame * t));
  EXPECT_NEAR(a.bulk_u, cfg.flow.bulk_velocity, 1e-12);  // the laboratory's flow rate in both
}

}  // namespace

TEST(MovingFrame, PipeFlowIsTheSameInTheLaboratory) { compare_frames(Geometry::Pipe, 1.7); }
TEST(MovingFrame, DuctFlowIsTheSameInTheLaboratory) { compare_frames(Geometry::Duct, -0.8); }
TEST(MovingFrame, ChannelFlowIsTheSameInTheLaboratory) { compare_frames(Geometry::Channel, 2.3); }

// Changing the frame mid-run is a Galilean shift: the laboratory's velocity is untouched.
TEST(MovingFrame, ChangingTheFrameShiftsOnlyTheGridVelocity) {
  CaseConfig cfg = test::small_case(Geometry::Pipe, 8, 16, 16, 1.0, 1.0, 1.0, 20.0, InitialFlow::Laminar);
  const Comm comm;
  const Grid grid = make_grid(cfg, comm);
  FlowSolver flow(cfg, grid, comm);
  flow.set_initial_condition();
  const FlowDiagnostics before = flow.diagnostics(1e-3);
  flow.set_frame_velocity(1.25, 0.0);
  flow.set_frame_velocity(0.5, 0.0);
  const FlowDiagnostics after = flow.diagnostics(1e-3);
  EXPECT_EQ(flow.frame_velocity(), 0.5);
  // the bulk velocity is a sum over ~1600 faces of O(1) values: round-off ~ sqrt(N) eps ~ 1e-14
  // (measured 1.5e-14 with the interpolated wall); a wrong shift would be O(1)
  EXPECT_NEAR(after.bulk_u, before.bulk_u, 1e-13);
  EXPECT_NEAR(after.kinetic_energy, before.kinetic_energy, 1e-14);
  EXPECT_LT(after.max_div, 1e-12);
}
