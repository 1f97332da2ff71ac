#pragma once
// Every Kokkos version switch lives here: one source for Kokkos 3.4 (Debian) and 4.x/5.x.
#include <Kokkos_Core.hpp>
#include <cmath>

namespace eulerfsi::compat {

// Kokkos 3.4 has no Kokkos::abs/min/max/sqrt in the main namespace; 4.x dropped the
// Experimental ones. The std:: functions are usable in device code on every backend we
// target only through Kokkos, so route everything through these shims.
#if KOKKOS_VERSION >= 40000
KOKKOS_INLINE_FUNCTION double sqrt(double x) { return Kokkos::sqrt(x); }
KOKKOS_INLINE_FUNCTION double fabs(double x) { return Kokkos::fabs(x); }
KOKKOS_INLINE_FUNCTION double cos(double x) { return Kokkos::cos(x); }
KOKKOS_INLINE_FUNCTION double sin(double x) { return Kokkos::sin(x); }
KOKKOS_INLINE_FUNCTION double asin(double x) { return Kokkos::asin(x); }
KOKKOS_INLINE_FUNCTION double pow(double x, double y) { return Kokkos::pow(x, y); }
KOKKOS_INLINE_FUNCTION bool isfinite(double x) { return Kokkos::isfinite(x); }
KOKKOS_INLINE_FUNCTION double floor(double x) { return Kokkos::floor(x); }
#else
KOKKOS_INLINE_FUNCTION double sqrt(double x) { return Kokkos::Experimental::sqrt(x); }
KOKKOS_INLINE_FUNCTION double fabs(double x) { return Kokkos::Experimental::fabs(x); }
KOKKOS_INLINE_FUNCTION double cos(double x) { return Kokkos::Experimental::cos(x); }
KOKKOS_INLINE_FUNCTION double sin(double x) { return Kokkos::Experimental::sin(x); }
KOKKOS_INLINE_FUNCTION double asin(double x) { return Kokkos::Experimental::asin(x); }
KOKKOS_INLINE_FUNCTION double pow(double x, double y) { return Kokkos::Experimental::pow(x, y); }
KOKKOS_INLINE_FUNCTION bool isfinite(double x) { return Kokkos::Experimental::isfinite(x); }
KOKKOS_INLINE_FUNCTION double floor(double x) { return Kokkos::Experimental::floor(x); }
#endif
KOKKOS_INLINE_FUNCTION double fmin(double a, double b) { return a < b ? a : b; }
KOKKOS_INLINE_FUNCTION double fmax(double a, double b) { return a > b ? a : b; }
KOKKOS_INLINE_FUNCTION int imin(int a, int b) { return a < b ? a : b; }
KOKKOS_INLINE_FUNCTION int imax(int a, int b) { return a > b ? a : b; }

// Kokkos::fence("label") appeared after 3.4.
inline void fence() { Kokkos::fence(); }

// The stream of the default device instance, for libraries (cuFFT, hipFFT) that must run in
// order with our kernels. HIP left Kokkos::Experimental in 4.0.
#ifdef KOKKOS_ENABLE_CUDA
inline cudaStream_t cuda_stream() { return Kokkos::Cuda().cuda_stream(); }
#endif
#ifdef KOKKOS_ENABLE_HIP
#if KOKKOS_VERSION >= 40000
inline hipStream_t hip_stream() { return Kokkos::HIP().hip_stream(); }
#else
inline hipStream_t hip_stream() { return Kokkos::Experimental::HIP().hip_stream(); }
#endif
#endif

// Name of the default execution space, for `eulerfsi info` and benchmark labels.
inline const char* default_backend_name() { return Kokkos::DefaultExecutionSpace::name(); }

}  // namespace eulerfsi::compat
