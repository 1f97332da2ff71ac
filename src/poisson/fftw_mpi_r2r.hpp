#pragma once
// A distributed 3-D real-to-real transform pair on the grid's x-slabs (FFTW-MPI), used to solve
// the diagonal problems of the fast solvers: (a + b L_h) x = f with L_h the 7-point Laplacian,
// whose eigenvectors are the transform's basis functions for the boundary rule of each direction:
//   Periodic  R2HC / HC2R          theta_m = 2 pi m / n      (m = 0 .. n-1, halfcomplex order)
//   EvenHalf  REDFT10 / REDFT01    theta_m = pi m / n        x(-1) = x(0): Neumann at the half-point
//   OddHalf   RODFT10 / RODFT01    theta_m = pi (m+1) / n    x(-1) = -x(0): zero at the half-point
//   OddFace   RODFT00 on n-1 faces theta_m = pi (m+1) / n    x(-1) = x(n-1) = 0: zero on the wall faces
// with eigenvalue lambda = -4 sin^2(theta / 2) / h^2 (FFTW 3 manual, "What FFTW Really Computes", for the
// definitions; the sine form avoids the cancellation of 2 (cos theta - 1) for small modes).
// The spectrum is left transposed (y distributed): the backward transform takes it back, which
// saves two of the four all-to-alls.
// Along a wall z (not periodic) the z transform is replaced by a direct solve of each z line of the
// x-y spectrum (AlongZ::Tridiagonal, the default there): the same 3-point operator with the same
// end rule, so the same solution to round-off, at ~4 ns per cell instead of a DCT pair (~15 ns at
// 128 x 64^2 on one core here); as in CaNS (Costa 2018, Comput. Math. Appl. 76).
#include <fftw3-mpi.h>
#include "parallel/mpi.hpp"

#include <cstddef>

#include "core/types.hpp"
#include "grid/grid.hpp"
#include "poisson/fft_planning.hpp"

namespace eulerfsi {

enum class R2rKind { Periodic, EvenHalf, OddHalf, OddFace };

// FFTW's threads and FFTW-MPI set up, once per process: before any plan, and before wisdom naming
// FFTW-MPI's algorithms is imported (FFTW refuses names it does not know yet).
void ensure_fftw_mpi_init();

class FftwMpiR2r {
 public:
  // Estimate plans deterministically and at once; Measure may pick a faster algorithm but can
  // differ between runs and rank counts in the last bits (poisson/fft_planning.hpp).
  using Planning = FftPlanning;
  // How z is solved: a tridiagonal solve per line where z is a wall direction, or always by transform.
  enum class AlongZ { Tridiagonal, Transform };

  // `who` names the caller in error messages. `shared`: an fftw_alloc_real'ed buffer of at least
  // buffer_size() doubles that several transforms used one after the other may share (not freed
  // here); null: this transform allocates its own.
  FftwMpiR2r(const Grid& grid, MPI_Comm comm, const R2rKind kind[3], Planning planning, const char* who,
             double* shared = nullptr, AlongZ along_z = AlongZ::Tridiagonal);
  // Doubles of the in-place buffer this transform needs on this rank.
  static size_t buffer_size(const Grid& grid, MPI_Comm comm, const R2rKind kind[3], AlongZ along_z = AlongZ::Tridiagonal);
  ~FftwMpiR2r();
  FftwMpiR2r(const FftwMpiR2r&) = delete;
  FftwMpiR2r& operator=(const FftwMpiR2r&) = delete;

  // Overwrites the unknowns of f (storage kGhost + [0, n_d), n_d one less along an OddFace
  // direction) with x = f / (a + b lambda), mode by mode; a mode whose denominator is exactly 0
  // (the Poisson zero mode) is set to 0. Ghosts are neither read nor written.
  void solve(const Field3& f, double a, double b);
  // The same with the unknowns already written into unknown_block() (f's interior as one contiguous
  // block, index (i, j, k) = storage (i, j, k) + kGhost): x goes into f's interior.
  void solve_gathered(const Field3& f, double a, double b);
  using Work3 = Kokkos::View<double***, Kokkos::LayoutRight, MemSpace>;
  const Work3& unknown_block() const { return work_; }
  // True when z is solved line by line (a wall z, AlongZ::Tridiagonal, at most kMaxLine unknowns).
  bool tridiagonal_z() const { return tridiagonal_z_; }

  static constexpr int kMaxLine = 1024;  // the z lines' scratch lives on each thread's stack

 private:
  static bool use_tridiagonal(const Grid& grid, const R2rKind kind[3], AlongZ along_z);
  void divide_eigenvalues(double a, double b);  // x, y and z transformed: one division per mode
  void solve_z_lines(double a, double b);       // x, y transformed: a tridiagonal solve per z line

  using HostBuffer3 = Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;
  using HostLine = Kokkos::View<double*, Kokkos::HostSpace>;
  static constexpr bool kHostAccessible = Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible;

  int n_[3] = {0, 0, 0};          // unknowns per direction (the transform sizes)
  int nx_local_ = 0;
  ptrdiff_t local_n1_ = 0;        // y-planes of the transposed spectrum on this rank
  ptrdiff_t local_1_start_ = 0;   // global y index of the first one
  double* buf_ = nullptr;         // fftw_malloc'ed, in place for both transforms
  bool owns_buffer_ = true;
  fftw_plan forward_ = nullptr;
  fftw_plan backward_ = nullptr;
  HostBuffer3 physical_;          // buf_ as (nx_local, n1, n2): the x-slab in physical space
  HostBuffer3 spectrum_;          // buf_ as (local_n1, n0, n2): FFTW_MPI_TRANSPOSED_OUT layout
  Work3 work_;                    // contiguous copy of the unknowns in MemSpace (aliases buf_ on hosts)
  HostLine lambda_[3];            // 1-D eigenvalues of the second difference, per direction
  double scale_ = 1.0;            // 1 / (logical size of each transform): FFTW does not normalise
  bool tridiagonal_z_ = false;
  R2rKind kind_z_ = R2rKind::Periodic;
  double h_z_ = 1.0;
};

}  // namespace eulerfsi
