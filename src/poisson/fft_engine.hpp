#pragma once
// Batched 1-D FFTs on contiguous lines in MemSpace: the only part of the FFT_DCT Poisson solver
// that differs between backends. One implementation is compiled per build:
// fft_engine_fftw.cpp (hosts), fft_engine_cufft.cpp (KOKKOS_ENABLE_CUDA), fft_engine_hipfft.cpp
// (KOKKOS_ENABLE_HIP).
//
// Layout: `batch` lines of length n back to back. Real lines hold n values, half-complex lines
// n/2 + 1 (modes 0..n/2 of a real signal), complex lines n. No transform is normalised:
//   forward  X(m) = sum_l x(l) exp(-2 pi i l m / n),   backward x(l) = sum_m X(m) exp(+2 pi i l m / n),
// so backward(forward(x)) = n x. Calls are ordered with the Kokkos kernels of ExecSpace() (same
// stream on GPUs, in-order on hosts); the caller fences only where the host reads the result.
#include <memory>
#include <string>

#include "core/types.hpp"

namespace eulerfsi {

using Complex = Kokkos::complex<double>;

class FftEngine {
 public:
  virtual ~FftEngine();
  // real (batch, n) -> half-complex (batch, n/2 + 1)
  virtual void r2c(int n, int batch, double* in, Complex* out) = 0;
  // half-complex (batch, n/2 + 1) -> real (batch, n); `in` may be overwritten
  virtual void c2r(int n, int batch, Complex* in, double* out) = 0;
  // complex (batch, n) in place; sign -1 (forward) or +1 (backward)
  virtual void c2c(int n, int batch, Complex* data, int sign) = 0;
  // "FFTW 3.3.10", "cuFFT 11.2", ...
  virtual std::string name() const = 0;
};

// The engine of this build (FFTW, cuFFT or hipFFT, chosen by CMake from the Kokkos backend).
std::unique_ptr<FftEngine> make_fft_engine();

}  // namespace eulerfsi
