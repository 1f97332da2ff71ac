#pragma once
// Exact 7-point Poisson solve on one rank with batched 1-D FFTs and Kokkos kernels: the solver
// of builds without MPI and of GPUs (cuFFT, hipFFT), where FFTW-MPI's host transforms would cost
// two host-device copies of every field per substep.
//
// The transforms that diagonalise L_h, one direction at a time (kernels/fft_lines.hpp):
//   wall y/z:     DCT-II by Makhoul's algorithm (reorder, real-to-complex FFT, twiddle), done first
//                 while the data are still real; eigenvalue -4 sin^2(pi m / 2N) / h^2;
//   periodic x:   real-to-complex FFT, modes m = 0..Nx/2; eigenvalue -4 sin^2(pi m / Nx) / h^2;
//   periodic y/z: complex FFT of the x-spectrum; eigenvalue -4 sin^2(pi m / N) / h^2.
// The backward transforms undo them in reverse order. Each engine transform is unnormalised
// and each inverse returns N times its input, so one factor 1/(Nx Ny Nz) in the division
// normalises the whole solve.
#include <memory>

#include "kernels/fft_lines.hpp"
#include "poisson/fft_engine.hpp"
#include "poisson/poisson_solver.hpp"

namespace eulerfsi {

class FftDctPoisson final : public PoissonSolver {
 public:
  // The grid must be whole on this rank (nx_local == Nx); throws std::invalid_argument otherwise.
  explicit FftDctPoisson(const Grid& grid);
  void solve(Field3 rhs_phi) override;
  const char* name() const override { return "fft-dct"; }
  std::string engine_name() const { return engine_->name(); }

  // The separate passes, public for the tests: DCT-II / its inverse (times N) along a wall axis of
  // a real (Nx, Ny, Nz) array, in place.
  void dct2(const fft_lines::Real3& x, int axis);
  void dct2_inverse(const fft_lines::Real3& x, int axis);

 private:
  void forward();   // real_ -> spec_
  void backward();  // spec_ -> real_ (times Nx Ny Nz)
  void divide_by_eigenvalues();
  void check_fits(const fft_lines::Real3& x, int axis) const;

  std::unique_ptr<FftEngine> engine_;
  int n_[3] = {0, 0, 0};
  bool wall_[3] = {false, false, false};
  fft_lines::Real3 real_;          // (Nx, Ny, Nz): f, then phi
  fft_lines::Complex3 spec_;       // (Nx/2 + 1, Ny, Nz): the spectrum
  fft_lines::RealBuffer lines_;    // engine input/output, real lines
  fft_lines::ComplexBuffer clines_;  // engine input/output, complex lines
  Line lambda_[3];                 // 1-D eigenvalues per direction, indexed by mode
  fft_lines::Twiddle twiddle_[3];  // DCT twiddle factors per direction (axes 1 and 2)
};

}  // namespace eulerfsi
