#include "poisson/fft_dct_poisson.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/compat.hpp"

namespace eulerfsi {

using namespace fft_lines;

namespace {

// Eigenvalues of (phi(p+1) - 2 phi(p) + phi(p-1)) / h^2 for the modes of this solver's transform:
// theta = 2 pi m / N (DFT, m < N; the real-to-complex x-spectrum uses m <= N/2) or pi m / N
// (DCT-II); -4 sin^2(theta/2) avoids the cancellation of 2(cos theta - 1) for small modes.
Line eigenvalues(int n, double h, bool wall, const char* label) {
  Line lam(std::string(label), n);
  auto host = Kokkos::create_mirror_view(lam);
  const double pi = 3.14159265358979323846;
  for (int m = 0; m < n; ++m) {
    const double s = std::sin(0.5 * (wall ? pi : 2.0 * pi) * m / n);
    host(m) = -4.0 * s * s / (h * h);
  }
  Kokkos::deep_copy(lam, host);
  return lam;
}

// The kernel of divide_by_eigenvalues, outside the class: nvcc refuses device lambdas in private
// member functions.
void divide_spectrum(const Complex3& spec, const Line& lx, const Line& ly, const Line& lz, double scale) {
  const int n[3] = {int(spec.extent(0)), int(spec.extent(1)), int(spec.extent(2))};
  Kokkos::parallel_for("eulerfsi::poisson::divide_eigenvalues", whole(n),
                       KOKKOS_LAMBDA(const int m, const int j, const int k) {
    const double lam = lx(m) + ly(j) + lz(k);
    spec(m, j, k) = lam == 0.0 ? Complex(0.0, 0.0) : spec(m, j, k) * (scale / lam);
  });
}

}  // namespace

FftDctPoisson::FftDctPoisson(const Grid& grid) : engine_(make_fft_engine()) {
  if (grid.nx_local != grid.n[0]) {
    throw std::invalid_argument("FftDctPoisson: the grid is split into x-slabs (" + std::to_string(grid.nx_local) +
                                " of " + std::to_string(grid.n[0]) + " planes here); this solver needs all of it on one rank");
  }
  for (int d = 0; d < 3; ++d) {
    n_[d] = grid.n[d];
    wall_[d] = grid.bc[d] == Boundary::Wall;
  }
  const int nx = n_[0], ny = n_[1], nz = n_[2], half = nx / 2 + 1;
  real_ = Real3(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("eulerfsi::poisson::real")), nx, ny, nz);
  spec_ = Complex3(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("eulerfsi::poisson::spec")), half, ny, nz);
  lines_ = RealBuffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("eulerfsi::poisson::lines")),
                      long(nx) * ny * nz);
  // the largest complex stage: the x-spectrum, or the half-complex lines of a wall DCT
  const long complex_size = std::max({long(half) * ny * nz, long(nx) * (ny / 2 + 1) * nz, long(nx) * ny * (nz / 2 + 1)});
  clines_ = ComplexBuffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("eulerfsi::poisson::clines")),
                          complex_size);
  const char* labels[3] = {"eulerfsi::poisson::lambda_x", "eulerfsi::poisson::lambda_y", "eulerfsi::poisson::lambda_z"};
  for (int d = 0; d < 3; ++d) lambda_[d] = eigenvalues(n_[d], grid.h[d], wall_[d], labels[d]);
  // the tests may run DCTs along periodic axes too: every axis but x gets its table
  for (int d = 1; d < 3; ++d) twiddle_[d] = make_twiddle(n_[d]);
}

void FftDctPoisson::check_fits(const Real3& x, int axis) const {
  const long n = long(x.size()), N = long(x.extent(axis));
  if (axis < 1 || axis > 2 || N != n_[axis] || n > long(lines_.size()) || n / N * (N / 2 + 1) > long(clines_.size()))
    throw std::invalid_argument("FftDctPoisson: DCTs run along y or z of an array no larger than the grid");
}

void FftDctPoisson::dct2(const Real3& x, int axis) {
  check_fits(x, axis);
  const int N = int(x.extent(axis)), count = int(x.size() / x.extent(axis));
  dct2_reorder(x, lines_, axis);
  engine_->r2c(N, count, lines_.data(), clines_.data());
  dct2_twiddle(clines_, x, axis, twiddle_[axis]);
}

void FftDctPoisson::dct2_inverse(const Real3& x, int axis) {
  check_fits(x, axis);
  const int N = int(x.extent(axis)), count = int(x.size() / x.extent(axis));
  dct3_twiddle(x, clines_, axis, twiddle_[axis]);
  engine_->c2r(N, count, clines_.data(), lines_.data());
  dct3_unorder(lines_, x, axis);
}

void FftDctPoisson::forward() {
  for (int d = 1; d < 3; ++d)
    if (wall_[d]) dct2(real_, d);
  gather(real_, lines_, 0);
  engine_->r2c(n_[0], n_[1] * n_[2], lines_.data(), clines_.data());
  scatter_half(clines_, spec_);
  const int half = n_[0] / 2 + 1;
  for (int d = 1; d < 3; ++d) {
    if (wall_[d]) continue;
    gather(spec_, clines_, d);
    engine_->c2c(n_[d], half * n_[1] * n_[2] / n_[d], clines_.data(), -1);
    scatter(clines_, spec_, d);
  }
}

void FftDctPoisson::backward() {
  const int half = n_[0] / 2 + 1;
  for (int d = 2; d >= 1; --d) {
    if (wall_[d]) continue;
    gather(spec_, clines_, d);
    engine_->c2c(n_[d], half * n_[1] * n_[2] / n_[d], clines_.data(), +1);
    scatter(clines_, spec_, d);
  }
  gather_half(spec_, clines_);
  engine_->c2r(n_[0], n_[1] * n_[2], clines_.data(), lines_.data());
  scatter(lines_, real_, 0);
  for (int d = 2; d >= 1; --d)
    if (wall_[d]) dct2_inverse(real_, d);
}

// hat(phi) = hat(f) / (lambda_x(m) + lambda_y(j) + lambda_z(k)) / (Nx Ny Nz); the zero mode
// (lambda = 0) is set to 0: it removes mean(f) and gives phi zero mean.
void FftDctPoisson::divide_by_eigenvalues() {
  divide_spectrum(spec_, lambda_[0], lambda_[1], lambda_[2], 1.0 / (double(n_[0]) * n_[1] * n_[2]));
}

void FftDctPoisson::solve(Field3 rhs_phi) {
  const int g = kGhost;
  Real3 real = real_;
  // the interior of rhs_phi as one contiguous (Nx, Ny, Nz) array
  Kokkos::parallel_for("eulerfsi::poisson::gather", whole(n_), KOKKOS_LAMBDA(const int i, const int j, const int k) {
    real(i, j, k) = rhs_phi(i + g, j + g, k + g);
  });
  forward();
  divide_by_eigenvalues();
  backward();
  // phi into the interior; ghosts stay as they were (the caller fills them)
  Kokkos::parallel_for("eulerfsi::poisson::scatter", whole(n_), KOKKOS_LAMBDA(const int i, const int j, const int k) {
    rhs_phi(i + g, j + g, k + g) = real(i, j, k);
  });
}

}  // namespace eulerfsi
