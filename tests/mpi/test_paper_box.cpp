// The paper model's box path (src/solid/paper_model.cpp) against its whole-slab form: the same
// run with psi, B and their buffers on a window around psi's support and every kernel on the boxes
// found from it, and with everything on the whole slab, must give the same psi, B, u and p to the
// last bit, and the same particle.csv rows. The cases exercise every edge of the box logic, with
// paper-model spheres carried several cells downstream on a grid at rest:
//  - pipe: one sphere straddling the periodic x boundary (its support reaches both x ends: the
//    boxes span x on one rank, and sit across the rank boundary on two) and one straddling
//    x = Lx/2 (the boundary between the two ranks' slabs);
//  - channel (walls in y, periodic z): one sphere with its edge 1.5 cells from the lower wall (the
//    window takes in the wall's ghosts) and one straddling the periodic z boundary;
//  - windows: a grid large enough for the windows to be smaller than the slab in every direction,
//    a sphere on the centreline carried ~10 cells downstream (its window moves, and on two ranks
//    crosses the slab boundary) and one near the lower wall.
//
// Exact equality holds on any number of threads for the fields: every rhs, update, clip and
// extension value is computed from the same inputs, and the clip's two global sums are taken in an
// order that the boxes' extra zero terms do not change (kernels::clip_volume_fraction_ordered).
// The diagnostics sum over the active box instead of the slab with Kokkos reductions, whose
// split among threads follows the box: their rows are bit for bit on one thread (every rank of the
// 2-rank test runs one) and within 1e-12 relative on several.
// Shrinking the rhs box by one cell (R = P grown by 2) gives differences of 1e-8..6e-8 in u, p and
// psi, and the extension's box by one 2e-7 in B: the psi that crosses the box's edge is ~1e-6.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/launch.hpp"
#include "solid/paper_model.hpp"
#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

SolidConfig paper_sphere(double d, const std::array<double, 3>& c) {
  SolidConfig s;
  s.diameter = d;
  s.center = c;
  s.We = 0.5;
  s.model = SolidModelKind::Paper;
  return s;
}

CaseConfig pipe_spheres() {
  CaseConfig cfg = test::small_case(Geometry::Pipe, 32, 24, 24, 4.0 / 3.0, 1.0, 1.0, 100.0, InitialFlow::Laminar);
  cfg.solids.push_back(paper_sphere(0.25, {0.02, 0.12, 0.0}));
  cfg.solids.push_back(paper_sphere(0.25, {2.0 / 3.0, -0.05, 0.08}));
  return cfg;
}

CaseConfig channel_spheres() {
  CaseConfig cfg = test::small_case(Geometry::Channel, 32, 24, 24, 4.0 / 3.0, 1.0, 1.0, 100.0, InitialFlow::Laminar);
  const double h = 1.0 / 24.0;
  cfg.solids.push_back(paper_sphere(0.25, {0.4, -0.5 + 0.125 + 1.5 * h, 0.0}));
  cfg.solids.push_back(paper_sphere(0.25, {0.85, 0.15, 0.49}));
  return cfg;
}

CaseConfig spheres_on_windows() {
  CaseConfig cfg = test::small_case(Geometry::Channel, 72, 48, 48, 1.5, 1.0, 1.0, 100.0, InitialFlow::Laminar);
  const double h = 1.0 / 48.0, d = 6.0 * h;
  cfg.solids.push_back(paper_sphere(d, {0.55, 0.02, -0.03}));
  cfg.solids.push_back(paper_sphere(d, {1.0, -0.5 + 0.5 * d + 1.5 * h, 0.0}));
  return cfg;
}

PaperModel& paper(SolidBody& body) {
  auto* model = dynamic_cast<PaperModel*>(body.model.get());
  if (!model) throw std::logic_error("not a paper-model body");
  return *model;
}

// Runs `steps` steps from t; the particle rows of every step, in order.
std::vector<double> steps_from(test::CoupledCase& c, double& t, int steps) {
  std::vector<double> rows;
  for (int n = 0; n < steps; ++n) {
    const double dt = c.flow.stable_dt(c.solids.max_wave_speed());
    c.flow.advance(t, dt, &c.solids);
    t += dt;
    const auto states = c.tracker.measure(c.solids, c.flow.state());
    for (size_t b = 0; b < states.size(); ++b) {
      const auto row = particle_row(n + 1, t, int(b), states[b]);
      rows.insert(rows.end(), row.begin(), row.end());
    }
  }
  return rows;
}

// The same from t = 0 with every body on its box path or on the whole slab.
std::vector<double> run(test::CoupledCase& c, bool whole_slab, int steps) {
  for (auto& body : c.solids.bodies()) paper(body).use_whole_slab(whole_slab, body);
  double t = 0.0;
  return steps_from(c, t, steps);
}

// What a restart does to the bodies: their stored fields' owned cells onto fresh whole-slab fields
// (a checkpoint holds the owned cells), then SolidPhase::restore (the flow stays as it is).
void restore_from_itself(test::CoupledCase& c) {
  const auto sources = c.solids.checkpoint_sources();
  const auto targets = c.solids.checkpoint_fields();
  ASSERT_EQ(sources.size(), targets.size());
  const Box owned = c.grid.interior();
  for (size_t f = 0; f < sources.size(); ++f) {
    ASSERT_EQ(sources[f].name, targets[f].first);
    const WindowField from = sources[f].field;
    const Field3 to = targets[f].second;
    const double outside = sources[f].outside;
    const Box w = from.window();
    for_each_cell("test::restore", owned, KOKKOS_LAMBDA(int i, int j, int k) {
      const bool held = i >= w.lo[0] && i < w.hi[0] && j >= w.lo[1] && j < w.hi[1] && k >= w.lo[2] && k < w.hi[2];
      to(i, j, k) = held ? from(i, j, k) : outside;
    });
  }
  Kokkos::fence();
  c.solids.restore(c.solids.checkpoint_scalars());
}

// Cell (i, j, k) of a field on a window, `outside` where the window does not hold it.
struct HostWindow {
  HostField3 h;
  Box w;
  double outside;
  HostWindow(const WindowField& f, double out)
      : h(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f.data)), w(f.window()), outside(out) {}
  double operator()(int i, int j, int k) const {
    const bool held = i >= w.lo[0] && i < w.hi[0] && j >= w.lo[1] && j < w.hi[1] && k >= w.lo[2] && k < w.hi[2];
    return held ? h(i - w.lo[0], j - w.lo[1], k - w.lo[2]) : outside;
  }
};

// max |a - b| over the owned cells of every rank, and max |a|.
void compare(const test::CoupledCase& a, const WindowField& fa, const WindowField& fb, double& diff, double& scale,
             double outside = 0.0) {
  const Box box = a.grid.interior();
  const HostWindow ha(fa, outside), hb(fb, outside);
  diff = scale = 0.0;
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int k = box.lo[2]; k < box.hi[2]; ++k) {
        diff = std::max(diff, std::fabs(ha(i, j, k) - hb(i, j, k)));
        scale = std::max(scale, std::fabs(ha(i, j, k)));
      }
  diff = a.comm.max(diff);
  scale = a.comm.max(scale);
}

const char* case_name(int c) { return c == 0 ? "pipe" : c == 1 ? "channel" : "windows"; }

}  // namespace

class PaperBox : public ::testing::TestWithParam<int> {};

TEST_P(PaperBox, SameBitsAsTheWholeSlab) {
  const int which = GetParam();
  const CaseConfig cfg = which == 0 ? pipe_spheres() : which == 1 ? channel_spheres() : spheres_on_windows();
  constexpr int kSteps = 60;
  test::CoupledCase boxed(cfg), whole(cfg);
  const std::vector<double> rows_boxed = run(boxed, false, kSteps);
  const std::vector<double> rows_whole = run(whole, true, kSteps);

  // each body's active box is smaller than the slab (the test would compare nothing otherwise)
  const Box slab = boxed.grid.interior();
  for (auto& body : boxed.solids.bodies()) {
    EXPECT_FALSE(paper(body).whole_slab());
    EXPECT_LT(body.model->active_box().size(), slab.size());
  }
  // both runs stayed bounded (comparing two blown-up runs would prove nothing)
  EXPECT_LT(test::max_abs_velocity(boxed), 3.0);
  EXPECT_LT(test::max_abs_velocity(whole), 3.0);

  double diff, scale;
  for (int c = 0; c < 3; ++c) {
    compare(boxed, boxed.flow.state().vel.c[c], whole.flow.state().vel.c[c], diff, scale);
    EXPECT_EQ(diff, 0.0) << "velocity component " << c << " (of max " << scale << ")";
  }
  compare(boxed, boxed.flow.state().p, whole.flow.state().p, diff, scale);
  EXPECT_EQ(diff, 0.0) << "pressure (of max " << scale << ")";
  for (size_t n = 0; n < cfg.solids.size(); ++n) {
    const auto& bb = boxed.solids.bodies()[n];
    const auto& bw = whole.solids.bodies()[n];
    compare(boxed, bb.psi, bw.psi, diff, scale);
    EXPECT_GT(scale, 0.99) << "body " << n << " has left the domain";
    EXPECT_EQ(diff, 0.0) << "psi of body " << n;
    for (int c = 0; c < kernels::kTensorComponents; ++c) {
      compare(boxed, bb.b.c[c], bw.b.c[c], diff, scale, c < 3 ? 1.0 : 0.0);
      EXPECT_EQ(diff, 0.0) << "B component " << c << " of body " << n << " (of max " << scale << ")";
      compare(boxed, bb.b_prev.c[c], bw.b_prev.c[c], diff, scale, c < 3 ? 1.0 : 0.0);
      EXPECT_EQ(diff, 0.0) << "B_prev component " << c << " of body " << n;
    }
  }

  // particle.csv's rows: bit for bit on one thread, round-off of the diagnostics' sums on more
  ASSERT_EQ(rows_boxed.size(), rows_whole.size());
  const bool one_thread = ExecSpace().concurrency() == 1;
  double worst = 0.0;
  for (size_t r = 0; r < rows_boxed.size(); ++r) {
    const double d = std::fabs(rows_boxed[r] - rows_whole[r]);
    worst = std::max(worst, d / std::max(std::fabs(rows_whole[r]), 1.0));
    if (one_thread) {
      EXPECT_EQ(rows_boxed[r], rows_whole[r]) << "particle.csv entry " << r;
    } else {
      // entries that cancel to ~0 (a radial force of a centred body) are measured against 1e-12
      EXPECT_LE(d, 1e-12 * std::max(std::fabs(rows_whole[r]), 1.0)) << "particle.csv entry " << r;
    }
  }

  if (boxed.comm.rank() == 0) {
    std::printf("%s: particle rows largest difference %.2e (relative, or absolute below 1; %s)\n", case_name(which), worst,
                one_thread ? "one thread" : "several threads");
    for (auto& body : boxed.solids.bodies()) {
      const Box w = body.psi.window(), a = body.model->active_box();
      std::printf("  window %d..%d x %d..%d x %d..%d (%ld of %ld cells), active box %ld, %d moves\n", w.lo[0], w.hi[0],
                  w.lo[1], w.hi[1], w.lo[2], w.hi[2], w.size(), boxed.grid.all().size(), a.size(),
                  paper(body).window_moves());
    }
  }
  // the third case's windows are smaller than the slab, and the carried sphere's moved with it
  if (which == 2) {
    for (const auto& body : boxed.solids.bodies()) EXPECT_LT(body.psi.window().size(), boxed.grid.all().size());
    EXPECT_GE(paper(boxed.solids.bodies()[0]).window_moves(), 1);
  }
}

INSTANTIATE_TEST_SUITE_P(PipeChannelWindows, PaperBox, ::testing::Values(0, 1, 2));

// A run continued after its bodies were restored as from a checkpoint (psi and B only, on the whole
// slab, then moved onto windows that may sit elsewhere; the RK3 memory 0, which the first
// substep's zeta = 0 never reads) matches the uninterrupted run bit for bit, with windows smaller
// than the slab.
TEST(PaperBoxRestart, ContinuesBitForBit) {
  const CaseConfig cfg = spheres_on_windows();
  test::CoupledCase straight(cfg), restarted(cfg);
  constexpr int kHalf = 15;
  double t_straight = 0.0, t_restarted = 0.0;
  steps_from(straight, t_straight, 2 * kHalf);
  steps_from(restarted, t_restarted, kHalf);
  restore_from_itself(restarted);
  for (auto& body : restarted.solids.bodies()) EXPECT_LT(body.psi.window().size(), restarted.grid.all().size());
  steps_from(restarted, t_restarted, kHalf);
  double diff, scale;
  for (int c = 0; c < 3; ++c) {
    compare(straight, straight.flow.state().vel.c[c], restarted.flow.state().vel.c[c], diff, scale);
    EXPECT_EQ(diff, 0.0) << "velocity component " << c;
  }
  for (size_t n = 0; n < cfg.solids.size(); ++n) {
    const auto& a = straight.solids.bodies()[n];
    const auto& b = restarted.solids.bodies()[n];
    compare(straight, a.psi, b.psi, diff, scale);
    EXPECT_EQ(diff, 0.0) << "psi of body " << n;
    for (int c = 0; c < kernels::kTensorComponents; ++c) {
      compare(straight, a.b.c[c], b.b.c[c], diff, scale, c < 3 ? 1.0 : 0.0);
      EXPECT_EQ(diff, 0.0) << "B component " << c << " of body " << n;
    }
  }
}
