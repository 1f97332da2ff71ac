#pragma once
// Exact 7-point Poisson solve with FFTW-MPI's distributed real-to-real transforms on x-slabs.
//
// One 3-D r2r transform diagonalises L_h: R2HC (real DFT) along periodic directions,
// REDFT10 (DCT-II) along wall directions, whose discrete Neumann condition phi(-1) = phi(0)
// is exactly the even extension about the wall that DCT-II assumes. FFTW does the global
// transpose; the spectrum is left transposed (y distributed) for the division and the
// backward transform takes it back, which saves two of the four all-to-alls.
#include <fftw3-mpi.h>
#include "parallel/mpi.hpp"

#include <cstddef>

#include "poisson/poisson_solver.hpp"

namespace eulerfsi {

class FftwMpiPoisson final : public PoissonSolver {
 public:
  // Estimate plans deterministically and at once; Measure may pick a faster algorithm but can
  // differ between runs and rank counts in the last bits.
  enum class Planning { Estimate, Measure };

  FftwMpiPoisson(const Grid& grid, MPI_Comm comm, Planning planning = Planning::Estimate);
  ~FftwMpiPoisson() override;
  FftwMpiPoisson(const FftwMpiPoisson&) = delete;
  FftwMpiPoisson& operator=(const FftwMpiPoisson&) = delete;

  void solve(Field3 rhs_phi) override;
  const char* name() const override { return "fftw-mpi"; }

 private:
  using HostBuffer3 = Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;
  using HostLine = Kokkos::View<double*, Kokkos::HostSpace>;
  using Work3 = Kokkos::View<double***, Kokkos::LayoutRight, MemSpace>;
  static constexpr bool kHostAccessible = Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible;

  int n_[3] = {0, 0, 0};
  int nx_local_ = 0;
  ptrdiff_t local_n1_ = 0;        // y-planes of the transposed spectrum on this rank
  ptrdiff_t local_1_start_ = 0;   // global y index of the first one
  double* buf_ = nullptr;         // fftw_malloc'ed, in-place for both transforms
  fftw_plan forward_ = nullptr;
  fftw_plan backward_ = nullptr;
  HostBuffer3 physical_;          // buf_ as (nx_local, Ny, Nz): the x-slab in physical space
  HostBuffer3 spectrum_;          // buf_ as (local_n1, Nx, Nz): FFTW_MPI_TRANSPOSED_OUT layout
  Work3 work_;                    // contiguous copy of the interior in MemSpace (aliases buf_ on hosts)
  HostLine lambda_[3];            // 1-D eigenvalues of the second difference, per direction
  double scale_ = 1.0;            // 1 / (product of N for periodic, 2N for wall): FFTW does not normalise
};

}  // namespace eulerfsi
