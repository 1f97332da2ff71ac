// The blow-up report names the field and the global cell of the first non-finite value, on
// every rank, whichever rank holds it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "app/fault_check.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

TEST(FaultCheck, NamesFieldAndGlobalCellOfTheFirstNaN) {
  const int cells[3] = {8, 6, 6};
  const double len[3] = {1.0, 1.0, 1.0};
  const Grid g(cells, len, Boundary::Wall, Boundary::Wall, test::rank(), test::nranks());
  Field3 u = g.make_field("u"), psi = g.make_field("psi");
  EXPECT_EQ(locate_non_finite({{"u", u}, {"psi", psi}}, g, MPI_COMM_WORLD), "");
  // a NaN in the last x-plane (owned by the last rank) at global cell (7, 2, 3)
  if (test::rank() == test::nranks() - 1) {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), psi);
    h(kGhost + g.nx_local - 1, kGhost + 2, kGhost + 3) = std::numeric_limits<double>::quiet_NaN();
    Kokkos::deep_copy(psi, h);
  }
  const std::string msg = locate_non_finite({{"u", u}, {"psi", psi}}, g, MPI_COMM_WORLD);
  EXPECT_NE(msg.find("field 'psi' is NaN at cell (7, 2, 3)"), std::string::npos) << msg;
}
