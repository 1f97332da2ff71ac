// The Poisson solvers against manufactured discrete solutions for every (y, z) boundary
// combination: FFTW-MPI on 1 and 2 ranks (the same expectations on both), FFT_DCT (r2c FFT +
// Makhoul DCT kernels) on 1 rank, and the two against each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "grid/grid.hpp"
#include "parallel/halo.hpp"
#include "parallel/mpi.hpp"
#include "poisson/fft_dct_poisson.hpp"
#include "poisson/poisson_solver.hpp"
#ifdef EULERFSI_HAVE_MPI
#include "poisson/fftw_mpi_poisson.hpp"
#include "poisson/fftw_mpi_r2r.hpp"
#endif
#include "support/field_compare.hpp"
#include "support/mpi_env.hpp"

namespace {
using eulerfsi::Boundary;
using eulerfsi::Field3;
using eulerfsi::Grid;
using eulerfsi::kGhost;

constexpr double kPi = 3.14159265358979323846;

struct Case {
  int n[3];
  double len[3];
  Boundary by, bz;
};

std::string case_name(const Case& c) {
  auto b = [](Boundary x) { return x == Boundary::Periodic ? "P" : "W"; };
  return std::to_string(c.n[0]) + "x" + std::to_string(c.n[1]) + "x" + std::to_string(c.n[2]) + "_y" + b(c.by) +
         "_z" + b(c.bz);
}

// The owned cell a (possibly ghost) global index stands for: periodic wrap, or the mirror
// phi(-1) = phi(0), phi(n) = phi(n-1) at a wall.
int canonical(int i, int n, Boundary bc) {
  if (bc == Boundary::Periodic) return ((i % n) + n) % n;
  if (i < 0) return -i - 1;
  if (i >= n) return 2 * n - 1 - i;
  return i;
}

// splitmix64: the same pseudo-random value for a global cell on any rank count
double noise(int i, int j, int k) {
  uint64_t z = (uint64_t(i) * 1000003ull + uint64_t(j)) * 1000033ull + uint64_t(k) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return double(z >> 11) * (1.0 / 9007199254740992.0) - 0.5;
}

// Smooth modes compatible with the BCs (cos about the walls) plus a rough random part and a
// constant. It depends on the canonical cell only, so ghost values obey the discrete BC
// exactly, x-periodicity across ranks included.
double phi_exact(const Grid& g, int gi, int gj, int gk) {
  const int i = canonical(gi, g.n[0], Boundary::Periodic);
  const int j = canonical(gj, g.n[1], g.bc[1]);
  const int k = canonical(gk, g.n[2], g.bc[2]);
  const double sx = (i + 0.5) / g.n[0], sy = (j + 0.5) / g.n[1], sz = (k + 0.5) / g.n[2];  // in (0, 1)
  auto mode = [](double s, Boundary bc, int m, double shift) {
    return bc == Boundary::Periodic ? std::sin(2.0 * kPi * m * s + shift) : std::cos(kPi * m * s);
  };
  return std::cos(2.0 * kPi * sx + 0.3) * mode(sy, g.bc[1], 1, 0.7) * mode(sz, g.bc[2], 2, 0.2) +
         0.5 * std::sin(4.0 * kPi * sx) * mode(sy, g.bc[1], 3, 1.1) + 0.25 * mode(sz, g.bc[2], 1, 0.4) +
         0.05 * noise(i, j, k) + 3.0;
}

// Largest over smallest nonzero eigenvalue of -L_h: the error amplification of an exact solver.
double condition_number(const Grid& g) {
  double lam_max = 0.0, lam_min = std::numeric_limits<double>::max();
  for (int d = 0; d < 3; ++d) {
    const double theta = (g.bc[d] == Boundary::Periodic ? 2.0 * kPi : kPi) / g.n[d];
    const double s = std::sin(0.5 * theta);
    lam_max += 4.0 / (g.h[d] * g.h[d]);
    lam_min = std::min(lam_min, 4.0 * s * s / (g.h[d] * g.h[d]));
  }
  return lam_max / lam_min;
}

double allreduce(double v, MPI_Op op) {
  double r = 0.0;
  MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, op, MPI_COMM_WORLD);
  return r;
}

using MakeSolver = std::function<std::unique_ptr<eulerfsi::PoissonSolver>(const Grid&)>;
const MakeSolver kDefault = [](const Grid& g) { return eulerfsi::make_poisson_solver(g, MPI_COMM_WORLD); };
const MakeSolver kFftDct = [](const Grid& g) { return std::make_unique<eulerfsi::FftDctPoisson>(g); };

struct Outcome {
  Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace> phi;  // with ghosts, filled
  double err = 0.0;       // max |phi - (phi_e - mean phi_e)|
  double res = 0.0;       // max |L_h phi - (f - mean f)|
  double max_phi = 0.0;   // max |phi_e - mean phi_e| (or |phi| for a random f)
  double max_f = 0.0;     // max |f - mean f|
  double mean_phi = 0.0;  // mean of the computed phi
  double cond = 0.0;
};

// Solves with f = L_h phi_exact (manufactured) or a random f with nonzero mean; checks on the
// host after exchange_x and a y/z ghost fill, as the time stepper would.
Outcome run(const Case& c, bool random_f, const MakeSolver& make = kDefault) {
  const int rank = eulerfsi::test::rank(), size = eulerfsi::test::nranks();
  const Grid g(c.n, c.len, c.by, c.bz, rank, size);
  const int e0 = g.ext(0), e1 = g.ext(1), e2 = g.ext(2);
  const int nx = g.nx_local, ny = g.n[1], nz = g.n[2];
  const double N = double(g.global_cells());
  auto gi = [&](int s) { return s - kGhost + g.x_offset; };
  auto gl = [&](int s) { return s - kGhost; };

  Field3 field = g.make_field("phi");
  auto h = Kokkos::create_mirror_view(field);
  Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace> f("f", e0, e1, e2);
  const double inv2[3] = {1.0 / (g.h[0] * g.h[0]), 1.0 / (g.h[1] * g.h[1]), 1.0 / (g.h[2] * g.h[2])};

  double sum_f = 0.0, sum_pe = 0.0;
  for (int i = kGhost; i < kGhost + nx; ++i)
    for (int j = kGhost; j < kGhost + ny; ++j)
      for (int k = kGhost; k < kGhost + nz; ++k) {
        const int a = gi(i), b = gl(j), cc = gl(k);
        if (random_f) {
          f(i, j, k) = noise(a, b, cc) + 1.0;
        } else {
          // f = L_h phi_e, the 7-point stencil with ghosts from the analytic, BC-respecting phi_e
          const double p = phi_exact(g, a, b, cc);
          f(i, j, k) = (phi_exact(g, a + 1, b, cc) - 2.0 * p + phi_exact(g, a - 1, b, cc)) * inv2[0] +
                       (phi_exact(g, a, b + 1, cc) - 2.0 * p + phi_exact(g, a, b - 1, cc)) * inv2[1] +
                       (phi_exact(g, a, b, cc + 1) - 2.0 * p + phi_exact(g, a, b, cc - 1)) * inv2[2];
          sum_pe += p;
        }
        sum_f += f(i, j, k);
      }
  const double mean_f = allreduce(sum_f, MPI_SUM) / N;
  const double mean_pe = allreduce(sum_pe, MPI_SUM) / N;

  // ghosts hold NaN: a solver that read them would poison the result
  Kokkos::deep_copy(h, std::numeric_limits<double>::quiet_NaN());
  for (int i = kGhost; i < kGhost + nx; ++i)
    for (int j = kGhost; j < kGhost + ny; ++j)
      for (int k = kGhost; k < kGhost + nz; ++k) h(i, j, k) = f(i, j, k);
  Kokkos::deep_copy(field, h);

  auto solver = make(g);
  solver->solve(field);
  eulerfsi::exchange_x(field, g, MPI_COMM_WORLD);
  Kokkos::deep_copy(h, field);

  // one y/z ghost layer per the BC is all the 7-point stencil needs
  for (int i = 0; i < e0; ++i) {
    for (int k = kGhost; k < kGhost + nz; ++k) {
      const bool p = g.bc[1] == Boundary::Periodic;
      h(i, kGhost - 1, k) = p ? h(i, kGhost + ny - 1, k) : h(i, kGhost, k);
      h(i, kGhost + ny, k) = p ? h(i, kGhost, k) : h(i, kGhost + ny - 1, k);
    }
    for (int j = kGhost; j < kGhost + ny; ++j) {
      const bool p = g.bc[2] == Boundary::Periodic;
      h(i, j, kGhost - 1) = p ? h(i, j, kGhost + nz - 1) : h(i, j, kGhost);
      h(i, j, kGhost + nz) = p ? h(i, j, kGhost) : h(i, j, kGhost + nz - 1);
    }
  }

  Outcome o;
  o.phi = h;
  double sum_phi = 0.0;
  for (int i = kGhost; i < kGhost + nx; ++i)
    for (int j = kGhost; j < kGhost + ny; ++j)
      for (int k = kGhost; k < kGhost + nz; ++k) {
        const double p = h(i, j, k);
        const double lap = (h(i + 1, j, k) - 2.0 * p + h(i - 1, j, k)) * inv2[0] +
                           (h(i, j + 1, k) - 2.0 * p + h(i, j - 1, k)) * inv2[1] +
                           (h(i, j, k + 1) - 2.0 * p + h(i, j, k - 1)) * inv2[2];
        const double ft = f(i, j, k) - mean_f;
        o.res = std::max(o.res, std::fabs(lap - ft));
        o.max_f = std::max(o.max_f, std::fabs(ft));
        if (random_f) {
          o.max_phi = std::max(o.max_phi, std::fabs(p));
        } else {
          const double ref = phi_exact(g, gi(i), gl(j), gl(k)) - mean_pe;
          o.err = std::max(o.err, std::fabs(p - ref));
          o.max_phi = std::max(o.max_phi, std::fabs(ref));
        }
        sum_phi += p;
      }
  // NaN compares false in max(): count it explicitly
  const double nan_flag = std::isfinite(o.res) && std::isfinite(sum_phi) ? 0.0 : 1.0;
  EXPECT_EQ(allreduce(nan_flag, MPI_MAX), 0.0) << "non-finite phi";
  o.err = allreduce(o.err, MPI_MAX);
  o.res = allreduce(o.res, MPI_MAX);
  o.max_phi = allreduce(o.max_phi, MPI_MAX);
  o.max_f = allreduce(o.max_f, MPI_MAX);
  o.mean_phi = allreduce(sum_phi, MPI_SUM) / N;
  o.cond = condition_number(g);
  if (rank == 0) {
    std::printf("[poisson] %-8s np=%d %-16s %s  err/max|phi_e| = %.2e  max|L phi - f|/max|f| = %.2e  "
                "mean(phi) = %.1e  tol = %.1e\n",
                solver->name(), size, case_name(c).c_str(), random_f ? "random f    " : "manufactured", o.err / o.max_phi,
                o.res / o.max_f, o.mean_phi, 64.0 * std::numeric_limits<double>::epsilon() * o.cond);
  }
  return o;
}

// Round-off bound of an exact transform solver: the transforms add a relative error of order
// eps log N (FFTW's error grows like log N) to every coefficient, and undoing L_h amplifies it at
// most by cond = lambda_max / lambda_min (dividing by small eigenvalues on the way in, multiplying
// by large ones in the residual). C = 64 covers log2 N <= 11, the max-vs-rms norm factor, and
// the two transforms. The cond factor is the worst case; measured errors on these grids are
// 1e-15 to 7e-15 relative, about three orders below the bound (2e-12 for cond = 150).
double tolerance(const Outcome& o) { return 64.0 * std::numeric_limits<double>::epsilon() * o.cond; }

class PoissonCases : public ::testing::TestWithParam<Case> {};

TEST_P(PoissonCases, RecoversManufacturedSolution) {
  const Outcome o = run(GetParam(), false);
  EXPECT_LE(o.err, tolerance(o) * o.max_phi);
  EXPECT_LE(o.res, tolerance(o) * o.max_f);
  EXPECT_LE(std::fabs(o.mean_phi), tolerance(o) * o.max_phi);
}

TEST_P(PoissonCases, RandomRhsResidualAtRoundOff) {
  // f has mean 1: the solver must remove it (compatibility) and return a zero-mean phi
  const Outcome o = run(GetParam(), true);
  EXPECT_LE(o.res, tolerance(o) * o.max_f);
  EXPECT_LE(std::fabs(o.mean_phi), tolerance(o) * o.max_phi);
}

const Boundary P = Boundary::Periodic, W = Boundary::Wall;
INSTANTIATE_TEST_SUITE_P(
    AllBoundaries, PoissonCases,
    ::testing::Values(
        // non-cubic cells (h = 0.125, 0.083, 0.08)
        Case{{16, 12, 10}, {2.0, 1.0, 0.8}, P, P}, Case{{16, 12, 10}, {2.0, 1.0, 0.8}, W, P},
        Case{{16, 12, 10}, {2.0, 1.0, 0.8}, P, W}, Case{{16, 12, 10}, {2.0, 1.0, 0.8}, W, W},
        // odd Ny, Nz: unequal y-blocks in the transposed spectrum, odd halfcomplex lengths
        Case{{12, 9, 7}, {1.0, 1.5, 0.7}, P, P}, Case{{12, 9, 7}, {1.0, 1.5, 0.7}, W, P},
        Case{{12, 9, 7}, {1.0, 1.5, 0.7}, P, W}, Case{{12, 9, 7}, {1.0, 1.5, 0.7}, W, W}),
    [](const ::testing::TestParamInfo<Case>& p) { return case_name(p.param); });

// FFT_DCT is a one-rank solver: on 2 ranks these tests have nothing to run.
#define SKIP_UNLESS_ONE_RANK() \
  if (eulerfsi::test::nranks() > 1) GTEST_SKIP() << "FFT_DCT runs on one rank"

TEST_P(PoissonCases, FftDctRecoversManufacturedSolution) {
  SKIP_UNLESS_ONE_RANK();
  const Outcome o = run(GetParam(), false, kFftDct);
  EXPECT_LE(o.err, tolerance(o) * o.max_phi);
  EXPECT_LE(o.res, tolerance(o) * o.max_f);
  EXPECT_LE(std::fabs(o.mean_phi), tolerance(o) * o.max_phi);
}

TEST_P(PoissonCases, FftDctRandomRhsResidualAtRoundOff) {
  SKIP_UNLESS_ONE_RANK();
  const Outcome o = run(GetParam(), true, kFftDct);
  EXPECT_LE(o.res, tolerance(o) * o.max_f);
  EXPECT_LE(std::fabs(o.mean_phi), tolerance(o) * o.max_phi);
}

#ifdef EULERFSI_HAVE_MPI
// The same random f through both solvers: the solutions agree to 1e-12 of max |phi|.
TEST_P(PoissonCases, FftDctAgreesWithFftwMpi) {
  SKIP_UNLESS_ONE_RANK();
  const MakeSolver fftw_mpi = [](const Grid& g) { return std::make_unique<eulerfsi::FftwMpiPoisson>(g, MPI_COMM_WORLD); };
  const Outcome a = run(GetParam(), true, fftw_mpi), b = run(GetParam(), true, kFftDct);
  double diff = 0.0;
  for (std::size_t i = kGhost; i < a.phi.extent(0) - kGhost; ++i)
    for (std::size_t j = kGhost; j < a.phi.extent(1) - kGhost; ++j)
      for (std::size_t k = kGhost; k < a.phi.extent(2) - kGhost; ++k) diff = std::max(diff, std::fabs(a.phi(i, j, k) - b.phi(i, j, k)));
  std::printf("[poisson] fft-dct vs fftw-mpi %-16s max|diff|/max|phi| = %.2e\n", case_name(GetParam()).c_str(),
              diff / a.max_phi);
  EXPECT_LE(diff, 1e-12 * a.max_phi);
}
#endif

TEST(Poisson, FactoryGivesTheBuildsSolver) {
  const int cells[3] = {12, 8, 8};
  const double len[3] = {1.0, 1.0, 1.0};
  const Grid g(cells, len, W, W, eulerfsi::test::rank(), eulerfsi::test::nranks());
#if defined(EULERFSI_POISSON_DEFAULT_FFT_DCT)
  // FFT_DCT on one rank; distributed runs take FFTW-MPI
  EXPECT_STREQ(eulerfsi::make_poisson_solver(g, MPI_COMM_WORLD)->name(),
               eulerfsi::test::nranks() == 1 ? "fft-dct" : "fftw-mpi");
#else
  EXPECT_STREQ(eulerfsi::make_poisson_solver(g, MPI_COMM_WORLD)->name(), "fftw-mpi");
#endif
}

#ifdef EULERFSI_HAVE_MPI
TEST(Poisson, RejectsGridOfAnotherDecomposition) {
  // a grid split for twice the ranks of the communicator: FFTW's slabs differ on every rank
  const int cells[3] = {24, 8, 8};
  const double len[3] = {1.0, 1.0, 1.0};
  const Grid g(cells, len, W, W, eulerfsi::test::rank(), 2 * eulerfsi::test::nranks());
  EXPECT_THROW(eulerfsi::FftwMpiPoisson(g, MPI_COMM_WORLD), std::runtime_error);
}
#endif

#ifdef EULERFSI_HAVE_MPI
// The z lines solved directly (Thomas) against the z transform, for every z end rule, the Poisson
// operator (a = 0, b = 1: the zero mode included) and a Helmholtz one (a = 1, b = -0.3), on odd and
// even line lengths and a one-unknown line: the same discrete problem, so the same solution to the
// 1e-12 of the solver comparison above (both are exact solvers; round-off ~eps cond, cond < 200).
TEST(FftwMpiR2r, TridiagonalZLinesAgreeWithTheZTransform) {
  using eulerfsi::FftwMpiR2r;
  using eulerfsi::R2rKind;
  const R2rKind z_kinds[3] = {R2rKind::EvenHalf, R2rKind::OddHalf, R2rKind::OddFace};
  const double ab[2][2] = {{0.0, 1.0}, {1.0, -0.3}};
  const int nzs[3] = {7, 10, 2};  // OddFace on 2 cells: one unknown
  for (const R2rKind kz : z_kinds)
    for (const int nz : nzs)
      for (const auto& coef : ab)
        for (const R2rKind ky : {R2rKind::Periodic, R2rKind::EvenHalf}) {
          const int cells[3] = {12, 9, nz};
          const double len[3] = {1.0, 0.9, 0.1 * nz};
          const Grid g(cells, len, W, W, eulerfsi::test::rank(), eulerfsi::test::nranks());
          const R2rKind kind[3] = {R2rKind::Periodic, ky, kz};
          FftwMpiR2r lines(g, MPI_COMM_WORLD, kind, FftwMpiR2r::Planning::Estimate, "test", nullptr,
                           FftwMpiR2r::AlongZ::Tridiagonal);
          FftwMpiR2r transform(g, MPI_COMM_WORLD, kind, FftwMpiR2r::Planning::Estimate, "test", nullptr,
                               FftwMpiR2r::AlongZ::Transform);
          ASSERT_TRUE(lines.tridiagonal_z());
          ASSERT_FALSE(transform.tridiagonal_z());
          Field3 x1 = g.make_field("x1"), x2 = g.make_field("x2");
          auto h1 = Kokkos::create_mirror_view(x1);
          const int x0 = g.x_offset;
          for (int i = 0; i < g.nx_local; ++i)
            for (int j = 0; j < g.n[1]; ++j)
              for (int k = 0; k < g.n[2]; ++k) h1(i + kGhost, j + kGhost, k + kGhost) = noise(x0 + i, j, k) + 0.5;
          Kokkos::deep_copy(x1, h1);
          Kokkos::deep_copy(x2, h1);
          lines.solve(x1, coef[0], coef[1]);
          transform.solve(x2, coef[0], coef[1]);
          auto r1 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x1);
          auto r2 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x2);
          const int nzu = kz == R2rKind::OddFace ? nz - 1 : nz;
          double diff = 0.0, size = 0.0;
          for (int i = 0; i < g.nx_local; ++i)
            for (int j = 0; j < g.n[1]; ++j)
              for (int k = 0; k < nzu; ++k) {
                const double a = r1(i + kGhost, j + kGhost, k + kGhost), b = r2(i + kGhost, j + kGhost, k + kGhost);
                diff = std::max(diff, std::fabs(a - b));
                size = std::max(size, std::fabs(b));
              }
          diff = allreduce(diff, MPI_MAX);
          size = allreduce(size, MPI_MAX);
          EXPECT_GT(size, 0.0);
          EXPECT_LE(diff, 1e-12 * size) << "z kind " << int(kz) << ", nz " << nz << ", a " << coef[0] << ", y kind "
                                        << int(ky);
        }
}
#endif

TEST(Poisson, FftDctRejectsASplitGrid) {
  const int cells[3] = {24, 8, 8};
  const double len[3] = {1.0, 1.0, 1.0};
  const Grid g(cells, len, W, P, 0, 2);
  EXPECT_THROW(eulerfsi::FftDctPoisson{g}, std::invalid_argument);
}

}  // namespace

#ifdef EULERFSI_HAVE_MPI
// FFTW-MPI writes the divergence straight into its own buffer (solve_divergence); the base class
// computes it into phi and calls solve(). Same arithmetic in the same order: equal to round-off of
// the solution's size (1e-13 of max |phi|, the Poisson test's own bound below the condition
// number). A box other than the rank's interior would write past the buffer: refused.
TEST(Poisson, DivergenceIntoTheBufferEqualsDivergenceThenSolve) {
  const int cells[3] = {24, 12, 10};
  const double len[3] = {2.0, 1.0, 1.0};
  const Grid g(cells, len, W, W, eulerfsi::test::rank(), eulerfsi::test::nranks());
  eulerfsi::FftwMpiPoisson solver(g, MPI_COMM_WORLD);
  Field3 vel[3] = {g.make_field("u"), g.make_field("v"), g.make_field("w")};
  for (int c = 0; c < 3; ++c) {
    auto h = Kokkos::create_mirror_view(vel[c]);
    for (int i = 0; i < g.ext(0); ++i)
      for (int j = 0; j < g.ext(1); ++j)
        for (int k = 0; k < g.ext(2); ++k) h(i, j, k) = noise(i - kGhost + g.x_offset + 100 * c, j, k);
    Kokkos::deep_copy(vel[c], h);
  }
  Field3 direct = g.make_field("phi_direct"), reference = g.make_field("phi_reference");
  const eulerfsi::Box box = g.interior();
  solver.solve_divergence(direct, vel[0], vel[1], vel[2], g.h, 0.7, box);
  solver.eulerfsi::PoissonSolver::solve_divergence(reference, vel[0], vel[1], vel[2], g.h, 0.7, box);
  const eulerfsi::test::FieldDifference d = eulerfsi::test::max_difference(direct, reference, box);
  const double diff = allreduce(d.diff, MPI_MAX), scale = allreduce(d.scale, MPI_MAX);
  EXPECT_GT(scale, 1e-3);
  EXPECT_LE(diff, 1e-13 * scale);
  eulerfsi::Box shrunk = box;
  shrunk.hi[2] -= 1;
  EXPECT_THROW(solver.solve_divergence(direct, vel[0], vel[1], vel[2], g.h, 0.7, shrunk), std::logic_error);
}
#endif
