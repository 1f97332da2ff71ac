// exchange_x fills the x-ghost planes from the periodic x-neighbours, whole planes included.
#include <gtest/gtest.h>
#include "parallel/mpi.hpp"

#include <algorithm>
#include <cmath>

#include "app/simulation.hpp"
#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "kernels/projection.hpp"
#include "parallel/comm.hpp"
#include "parallel/halo.hpp"
#include "solver/boundary_conditions.hpp"
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

// After a predictor changes the owned velocity (the high wall's face included), the divergence
// read through fill_divergence_stencil equals the one read through a whole fill_velocity, bit for
// bit: walls in y and z (duct) and a periodic z (channel), on 1 and 2 ranks.
void expect_divergence_stencil_is_enough(eulerfsi::Geometry geometry) {
  using namespace eulerfsi;
  CaseConfig cfg;
  cfg.source = "<test>";
  cfg.domain.geometry = geometry;
  cfg.domain.cells = {12, 6, 5};
  cfg.domain.length = {2.0, 1.0, 1.0};
  const Comm comm;
  const Grid g = make_grid(cfg, comm);
  const BoundaryConditions bc(cfg, g, comm.comm);
  kernels::Velocity full, partial;
  for (int c = 0; c < 3; ++c) {
    full.c[c] = g.make_field("u");
    auto h = Kokkos::create_mirror_view(full.c[c]);
    // the state after the last substep: owned values, then every ghost filled
    for (int i = 0; i < g.ext(0); ++i)
      for (int j = 0; j < g.ext(1); ++j)
        for (int k = 0; k < g.ext(2); ++k) h(i, j, k) = std::sin(1.0 + c + 0.3 * (i + g.x_offset) + 0.7 * j + 1.1 * k);
    Kokkos::deep_copy(full.c[c], h);
  }
  bc.fill_velocity(full, 0.0);
  for (int c = 0; c < 3; ++c) {
    // a predictor: every owned value changes, ghosts stay as the last fill left them
    auto h = Kokkos::create_mirror_view(full.c[c]);
    Kokkos::deep_copy(h, full.c[c]);
    for (int i = kGhost; i < kGhost + g.nx_local; ++i)
      for (int j = kGhost; j < kGhost + g.n[1]; ++j)
        for (int k = kGhost; k < kGhost + g.n[2]; ++k) h(i, j, k) += 0.25 * std::cos(2.0 * c + 0.9 * i + 0.4 * j - 0.6 * k);
    Kokkos::deep_copy(full.c[c], h);
    partial.c[c] = g.make_field("u_partial");
    Kokkos::deep_copy(partial.c[c], full.c[c]);
  }
  bc.fill_velocity(full, 0.0);
  bc.fill_divergence_stencil(partial);
  const double h[3] = {g.h[0], g.h[1], g.h[2]};
  auto div_full = g.make_field("div_full"), div_partial = g.make_field("div_partial");
  kernels::divergence(div_full, full.c[0], full.c[1], full.c[2], h, 1.0, g.interior());
  kernels::divergence(div_partial, partial.c[0], partial.c[1], partial.c[2], h, 1.0, g.interior());
  auto a = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), div_full);
  auto b = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), div_partial);
  int differ = 0;
  double largest = 0.0;
  for (int i = kGhost; i < kGhost + g.nx_local; ++i)
    for (int j = kGhost; j < kGhost + g.n[1]; ++j)
      for (int k = kGhost; k < kGhost + g.n[2]; ++k) {
        differ += a(i, j, k) != b(i, j, k);
        largest = std::max(largest, std::abs(a(i, j, k)));
      }
  EXPECT_EQ(comm.sum(long(differ)), 0L);
  // the perturbation is not divergence-free: the comparison sees the stencil's every input
  EXPECT_GT(comm.max(largest), 0.1);
}

TEST(Halo, DivergenceStencilFillMatchesTheFullFillInADuct) {
  expect_divergence_stencil_is_enough(eulerfsi::Geometry::Duct);
}

TEST(Halo, DivergenceStencilFillMatchesTheFullFillInAChannel) {
  expect_divergence_stencil_is_enough(eulerfsi::Geometry::Channel);
}

}  // namespace
