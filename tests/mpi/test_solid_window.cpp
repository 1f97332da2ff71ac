// The window a reference-map body's fields live on (src/solid/solid_window.hpp): where it goes
// for a given need (its rules at walls, periodic ends and x-slab boundaries), that a move keeps
// every value it still holds and puts the "outside" value everywhere else, and that it shrinks
// again once the body has left a wall or the periodic end. On 1 and 2 ranks (one global window,
// each rank holding its slab's part). The coupled runs on windows are tested against the whole
// slab in test_active_box.cpp.
#include <gtest/gtest.h>

#include <vector>

#include "solid/solid_window.hpp"
#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

// Channel 48 x 40 x 40: walls in y, periodic z; x-slabs over the ranks.
Grid channel(const Comm& comm) {
  const CaseConfig cfg = test::small_case(Geometry::Channel, 48, 40, 40, 1.2, 1.0, 1.0, 100.0, InitialFlow::Laminar);
  return make_grid(cfg, comm);
}

// A need in global storage indices given as this rank's numbering (x shifted by its offset).
Box local_need(const Grid& g, Box global) {
  global.lo[0] -= g.x_offset;
  global.hi[0] -= g.x_offset;
  return global;
}

// f = 1000 i_global + 10 j + k / 10 on every cell the field holds.
void fill_pattern(const Grid& g, const WindowField& f) {
  const int x0 = g.x_offset;
  Kokkos::parallel_for("test::pattern", f.window().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
    f(i, j, k) = 1000.0 * (i + x0) + 10.0 * j + 0.1 * k;
  });
  Kokkos::fence();
}

}  // namespace

TEST(SolidWindow, PlacementFollowsTheRules) {
  const Comm comm;
  const Grid g = channel(comm);
  const int ext[3] = {48 + 2 * kGhost, 40 + 2 * kGhost, 40 + 2 * kGhost};
  // in the middle: the need grown by the slack of 2, nothing else
  Box w = SolidWindow::placement(g, Box{{20, 15, 15}, {30, 25, 25}});
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(w.lo[d], (d == 0 ? 20 : 15) - 2);
    EXPECT_EQ(w.hi[d], (d == 0 ? 30 : 25) + 2);
  }
  // reaching the first owned cells next to the low y wall: that wall's ghosts only
  w = SolidWindow::placement(g, Box{{20, 6, 15}, {30, 16, 25}});
  EXPECT_EQ(w.lo[1], 0);
  EXPECT_EQ(w.hi[1], 18);
  // near the periodic z end, or the x end: the whole direction
  w = SolidWindow::placement(g, Box{{20, 15, 30}, {30, 25, 41}});
  EXPECT_EQ(w.lo[2], 0);
  EXPECT_EQ(w.hi[2], ext[2]);
  w = SolidWindow::placement(g, Box{{6, 15, 15}, {16, 25, 25}});
  EXPECT_EQ(w.lo[0], 0);
  EXPECT_EQ(w.hi[0], ext[0]);
}

TEST(SolidWindow, MovesKeepValuesAndShrinkBack) {
  const Comm comm;
  const Grid g = channel(comm);
  SolidWindow window(g, comm);
  WindowField f;
  const double outside = -7.0;
  const std::vector<SolidWindow::Member> members = {{&f, outside, "f"}};

  ASSERT_TRUE(window.hold(local_need(g, Box{{15, 15, 15}, {25, 25, 25}}), members));
  fill_pattern(g, f);
  const Box before = f.window();
  // the body moves 4 cells along x and 3 along y: the window moves with it
  ASSERT_TRUE(window.hold(local_need(g, Box{{19, 18, 15}, {29, 28, 25}}), members));
  const Box after = f.window();
  auto host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f.data);
  long kept = 0, bad = 0;
  for (int i = after.lo[0]; i < after.hi[0]; ++i)
    for (int j = after.lo[1]; j < after.hi[1]; ++j)
      for (int k = after.lo[2]; k < after.hi[2]; ++k) {
        const bool held = i >= before.lo[0] && i < before.hi[0] && j >= before.lo[1] && j < before.hi[1] &&
                          k >= before.lo[2] && k < before.hi[2];
        const double want = held ? 1000.0 * (i + g.x_offset) + 10.0 * j + 0.1 * k : outside;
        kept += held;
        bad += host(i - after.lo[0], j - after.lo[1], k - after.lo[2]) != want;
      }
  EXPECT_EQ(comm.sum(bad), 0L) << "values not kept, or not 'outside' on the new cells";
  EXPECT_GT(comm.sum(kept), 0L);
  // a need inside the window: no move
  EXPECT_FALSE(window.hold(local_need(g, Box{{20, 19, 16}, {28, 27, 24}}), members));

  // next to the x end the window takes every x-plane; back in the middle it shrinks again
  ASSERT_TRUE(window.hold(local_need(g, Box{{40, 15, 15}, {50, 25, 25}}), members));
  const long whole_x = comm.sum(long(f.window().size()));
  EXPECT_EQ(whole_x, long(48 + 2 * kGhost * comm.size()) * 14 * 14);
  ASSERT_TRUE(window.hold(local_need(g, Box{{20, 15, 15}, {30, 25, 25}}), members));
  EXPECT_LT(comm.sum(long(f.window().size())), whole_x / 2);
  EXPECT_EQ(window.moves(), 4);
}
