// The Makhoul DCT passes of the FFT_DCT Poisson solver: DCT-II equal to FFTW's REDFT10 along each
// wall axis, for even and odd lengths, and the inverse pass giving back N times the input.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>
#if !defined(KOKKOS_ENABLE_CUDA) && !defined(KOKKOS_ENABLE_HIP)
#include <fftw3.h>
#endif

#include "grid/grid.hpp"
#include "poisson/fft_dct_poisson.hpp"

namespace {
using eulerfsi::Boundary;
using eulerfsi::FftDctPoisson;
using eulerfsi::Grid;
using Real3 = eulerfsi::fft_lines::Real3;

// A host copy that never aliases x (create_mirror_view would return x itself on host backends).
Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace> host_copy(const Real3& x) {
  Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace> h("eulerfsi::test::copy", x.extent(0), x.extent(1),
                                                                     x.extent(2));
  Kokkos::deep_copy(h, x);
  return h;
}

// x(i, j, k): rough and different in every cell
Real3 sample(int nx, int ny, int nz) {
  Real3 x("eulerfsi::test::x", nx, ny, nz);
  auto h = Kokkos::create_mirror_view(x);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) h(i, j, k) = std::sin(1.3 * i + 0.7 * j * j + 2.1 * k) + 0.1 * ((i * 7 + j * 3 + k) % 5);
  Kokkos::deep_copy(x, h);
  return x;
}

class MakhoulDct : public ::testing::TestWithParam<std::array<int, 3>> {};

#if !defined(KOKKOS_ENABLE_CUDA) && !defined(KOKKOS_ENABLE_HIP)
TEST_P(MakhoulDct, EqualsFftwRedft10) {
  const auto n = GetParam();
  const double len[3] = {1.0, 1.0, 1.0};
  FftDctPoisson solver(Grid(n.data(), len, Boundary::Wall, Boundary::Wall, 0, 1));
  for (int axis = 1; axis < 3; ++axis) {
    Real3 x = sample(n[0], n[1], n[2]);
    auto ref = host_copy(x);
    solver.dct2(x, axis);
    auto got = host_copy(x);
    // REDFT10 line by line on the host: Y(m) = 2 sum_p x(p) cos(pi (2p + 1) m / 2N)
    const int N = n[axis];
    std::vector<double> in(N), out(N);
    fftw_plan plan = fftw_plan_r2r_1d(N, in.data(), out.data(), FFTW_REDFT10, FFTW_ESTIMATE);
    double err = 0.0, scale = 0.0;
    const int other = axis == 1 ? 2 : 1;
    for (int i = 0; i < n[0]; ++i)
      for (int q = 0; q < n[other]; ++q) {
        auto at = [&](auto& v, int p) -> double& { return axis == 1 ? v(i, p, q) : v(i, q, p); };
        for (int p = 0; p < N; ++p) in[p] = at(ref, p);
        fftw_execute(plan);
        for (int m = 0; m < N; ++m) {
          err = std::max(err, std::fabs(at(got, m) - out[m]));
          scale = std::max(scale, std::fabs(out[m]));
        }
      }
    fftw_destroy_plan(plan);
    EXPECT_LE(err, 1e-14 * N * scale) << "axis " << axis << ", N = " << N;
  }
}
#endif

TEST_P(MakhoulDct, InverseGivesBackNTimesTheInput) {
  const auto n = GetParam();
  const double len[3] = {1.0, 1.0, 1.0};
  FftDctPoisson solver(Grid(n.data(), len, Boundary::Wall, Boundary::Wall, 0, 1));
  for (int axis = 1; axis < 3; ++axis) {
    Real3 x = sample(n[0], n[1], n[2]);
    auto ref = host_copy(x);
    solver.dct2(x, axis);
    solver.dct2_inverse(x, axis);
    auto got = host_copy(x);
    const double N = n[axis];
    double err = 0.0;
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < n[2]; ++k) err = std::max(err, std::fabs(got(i, j, k) / N - ref(i, j, k)));
    EXPECT_LE(err, 1e-14 * N) << "axis " << axis;
  }
}

// even and odd lengths along both wall axes (odd N has no Nyquist mode)
INSTANTIATE_TEST_SUITE_P(Lengths, MakhoulDct,
                         ::testing::Values(std::array<int, 3>{4, 8, 6}, std::array<int, 3>{6, 7, 5},
                                           std::array<int, 3>{4, 1 + 2, 16}));

}  // namespace
