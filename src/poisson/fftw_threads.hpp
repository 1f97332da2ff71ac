#pragma once
// FFTW's threads are set up once per process, before any plan (and before fftw_mpi_init).
#include <fftw3.h>

namespace eulerfsi {

inline void fftw_threads_once() {
#ifdef EULERFSI_FFTW_THREADS
  // an inline function's static is one object in the whole program and initialised once
  static const bool done = [] { return fftw_init_threads() != 0; }();
  (void)done;
#endif
}

}  // namespace eulerfsi
