// The implicit-viscosity solve (I - c L_h) x = f for each velocity component, against a random
// x that obeys the component's homogeneous wall rule (tangential: x(-1) = -x(0); wall-normal, on
// the faces: zero on the wall faces), for every (y, z) boundary combination, on 1 and 2 ranks.
// The solver is exact: the error is round-off times the condition number 1 + c max|lambda|.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "grid/grid.hpp"
#include "parallel/mpi.hpp"
#include "poisson/helmholtz_solver.hpp"
#include "support/mpi_env.hpp"

#ifdef EULERFSI_HAVE_MPI
namespace {
using eulerfsi::Boundary;
using eulerfsi::Field3;
using eulerfsi::Grid;
using eulerfsi::kGhost;

// splitmix64: the same pseudo-random value for a global point on any rank count
double noise(int i, int j, int k, int c) {
  uint64_t z = ((uint64_t(i) * 1000003ull + uint64_t(j)) * 1000033ull + uint64_t(k)) * 7ull + uint64_t(c) +
               0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return double(z >> 11) * (1.0 / 9007199254740992.0) - 0.5;
}

// The unknown a (possibly ghost) index along one direction stands for, and the sign it carries;
// false for a wall face (value zero).
bool canonical(int& i, double& sign, int n, Boundary bc, bool normal) {
  if (bc == Boundary::Periodic) {
    i = ((i % n) + n) % n;
    return true;
  }
  if (normal) {  // faces 0 .. n-2 are unknowns; -1 and n-1 are the walls
    if (i == -1 || i == n - 1) return false;
    if (i < -1) i = -2 - i, sign = -sign;
    if (i > n - 1) i = 2 * (n - 1) - i, sign = -sign;
    return true;
  }
  if (i < 0) i = -i - 1, sign = -sign;
  if (i >= n) i = 2 * n - 1 - i, sign = -sign;
  return true;
}

double x_exact(const Grid& g, int comp, int i, int j, int k) {
  double sign = 1.0;
  int idx[3] = {i, j, k};
  for (int d = 0; d < 3; ++d)
    if (!canonical(idx[d], sign, g.n[d], g.bc[d], d == comp)) return 0.0;
  return sign * noise(idx[0], idx[1], idx[2], comp);
}

struct Case {
  Boundary by, bz;
};

class Helmholtz : public ::testing::TestWithParam<Case> {};

TEST_P(Helmholtz, SolvesEachComponentToRoundOff) {
  const int rank = eulerfsi::test::rank(), size = eulerfsi::test::nranks();
  const int n[3] = {16, 12, 10};
  const double len[3] = {2.0, 1.0, 0.8};
  const Grid g(n, len, GetParam().by, GetParam().bz, rank, size);
  auto solver = eulerfsi::make_helmholtz_solver(g, MPI_COMM_WORLD);
  // c of a viscous step well past the explicit limit (dt mu / h^2 ~ 4): condition number ~ 100
  const double c = 4.0 * g.h[1] * g.h[1];
  double cond = 1.0;
  for (int d = 0; d < 3; ++d) cond += c * 4.0 / (g.h[d] * g.h[d]);
  const double inv2[3] = {1.0 / (g.h[0] * g.h[0]), 1.0 / (g.h[1] * g.h[1]), 1.0 / (g.h[2] * g.h[2])};

  for (int comp = 0; comp < 3; ++comp) {
    Field3 field = g.make_field("x");
    auto h = Kokkos::create_mirror_view(field);
    const int hi[3] = {g.nx_local, g.n[1] - (g.bc[1] == Boundary::Wall && comp == 1),
                       g.n[2] - (g.bc[2] == Boundary::Wall && comp == 2)};
    auto X = [&](int i, int j, int k) { return x_exact(g, comp, i + g.x_offset, j, k); };
    // f = x - c L_h x on the unknowns
    for (int i = 0; i < hi[0]; ++i)
      for (int j = 0; j < hi[1]; ++j)
        for (int k = 0; k < hi[2]; ++k) {
          const double x = X(i, j, k);
          const double lap = (X(i + 1, j, k) - 2 * x + X(i - 1, j, k)) * inv2[0] +
                             (X(i, j + 1, k) - 2 * x + X(i, j - 1, k)) * inv2[1] +
                             (X(i, j, k + 1) - 2 * x + X(i, j, k - 1)) * inv2[2];
          h(i + kGhost, j + kGhost, k + kGhost) = x - c * lap;
        }
    Kokkos::deep_copy(field, h);
    solver->solve(comp, field, c);
    Kokkos::deep_copy(h, field);
    double err = 0.0, scale = 0.0;
    for (int i = 0; i < hi[0]; ++i)
      for (int j = 0; j < hi[1]; ++j)
        for (int k = 0; k < hi[2]; ++k) {
          err = std::max(err, std::fabs(h(i + kGhost, j + kGhost, k + kGhost) - X(i, j, k)));
          scale = std::max(scale, std::fabs(X(i, j, k)));
        }
    double e = 0.0, s = 0.0;
    MPI_Allreduce(&err, &e, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    MPI_Allreduce(&scale, &s, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    // an exact solver: round-off of the transforms (a few eps log N) times the condition number
    const double tol = 64.0 * std::numeric_limits<double>::epsilon() * cond * s;
    if (rank == 0) std::printf("component %d: max error %.2e (bound %.2e, condition number %.0f)\n", comp, e, tol, cond);
    EXPECT_LE(e, tol) << "component " << comp;
  }
}

INSTANTIATE_TEST_SUITE_P(Walls, Helmholtz,
                         ::testing::Values(Case{Boundary::Periodic, Boundary::Periodic},
                                           Case{Boundary::Wall, Boundary::Periodic},
                                           Case{Boundary::Wall, Boundary::Wall}));
}  // namespace
#else
TEST(Helmholtz, RefusedWithoutMpi) {
  const int n[3] = {8, 8, 8};
  const double len[3] = {1.0, 1.0, 1.0};
  const eulerfsi::Grid g(n, len, eulerfsi::Boundary::Wall, eulerfsi::Boundary::Wall, 0, 1);
  EXPECT_THROW(eulerfsi::make_helmholtz_solver(g, MPI_COMM_WORLD), std::runtime_error);
}
#endif
