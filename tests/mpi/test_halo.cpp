// exchange_x fills the x-ghost planes from the periodic x-neighbours, whole planes included.
#include <gtest/gtest.h>
#include "parallel/mpi.hpp"

#include "grid/grid.hpp"
#include "parallel/halo.hpp"
#include "support/mpi_env.hpp"

namespace {
using eulerfsi::Boundary;
using eulerfsi::Grid;
using eulerfsi::kGhost;

// A value that names its global x-plane and its (j, k) storage position.
double tag(int global_i, int j, int k) { return 10000.0 * global_i + 100.0 * j + k; }

TEST(Halo, ExchangeXIsPeriodicAcrossRanks) {
  const int cells[3] = {12, 5, 4};
  const double len[3] = {1.0, 1.0, 1.0};
  const Grid g(cells, len, Boundary::Wall, Boundary::Periodic, eulerfsi::test::rank(), eulerfsi::test::nranks());
  auto f = g.make_field("f");
  auto h = Kokkos::create_mirror_view(f);
  Kokkos::deep_copy(h, -1.0);
  for (int i = kGhost; i < kGhost + g.nx_local; ++i)
    for (int j = 0; j < g.ext(1); ++j)
      for (int k = 0; k < g.ext(2); ++k) h(i, j, k) = tag(i - kGhost + g.x_offset, j, k);
  Kokkos::deep_copy(f, h);
  eulerfsi::exchange_x(f, g, MPI_COMM_WORLD);
  Kokkos::deep_copy(h, f);
  int bad = 0;
  for (int i = 0; i < g.ext(0); ++i) {
    const int gi = ((i - kGhost + g.x_offset) % g.n[0] + g.n[0]) % g.n[0];
    for (int j = 0; j < g.ext(1); ++j)
      for (int k = 0; k < g.ext(2); ++k) bad += h(i, j, k) != tag(gi, j, k);
  }
  EXPECT_EQ(bad, 0);
}

}  // namespace
