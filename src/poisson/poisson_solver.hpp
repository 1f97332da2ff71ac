#pragma once
// The pressure Poisson solve behind one small interface, so a cuFFT/hipFFT backend can
// replace FFTW without touching the time stepper.
#include "parallel/mpi.hpp"

#include <memory>
#include <string>

#include "core/types.hpp"
#include "grid/grid.hpp"
#include "kernels/projection.hpp"
#include "poisson/fft_planning.hpp"

namespace eulerfsi {

// Solves L_h phi = f exactly (to round-off), L_h the 7-point Laplacian on cell centres:
//   sum_d (phi(i+e_d) - 2 phi(i) + phi(i-e_d)) / h_d^2,
// periodic in x; in y and z periodic or homogeneous Neumann with the ghost convention
// phi(-1) = phi(0), phi(n) = phi(n-1) (the wall lies between cell 0 and its ghost).
// The mean of f over all cells is removed (the compatibility condition of the periodic /
// Neumann problem) and phi is returned with zero mean (the zero mode is fixed to 0).
class PoissonSolver {
 public:
  virtual ~PoissonSolver();
  // Reads f from the interior (storage indices kGhost .. kGhost+n-1) of rhs_phi and overwrites
  // that interior with phi. Ghosts are neither read nor filled: the caller fills them.
  virtual void solve(Field3 rhs_phi) = 0;
  // The projection's solve: f = scale div(u, v, w) (kernels/projection.hpp) on the interior box,
  // then phi into the interior of `phi`, as divergence + solve(phi) do. A solver with its own
  // buffer writes f straight into it (one pass over the grid less). Returns this rank's open-face
  // sum of u, taken in the divergence's pass when flow is active (0 otherwise).
  virtual double solve_divergence(Field3 phi, const Field3& u, const Field3& v, const Field3& w, const double h[3],
                                  double scale, const Box& interior, const kernels::OpenFaceSum& flow = {});
  virtual const char* name() const = 0;
};

// The best solver available for this build (today: FFTW-MPI on x-slabs). `planning` applies to
// FFTW-MPI; FFT_DCT's engines plan as they always do (FFTW: estimate) and ignore it.
std::unique_ptr<PoissonSolver> make_poisson_solver(const Grid& grid, MPI_Comm comm,
                                                   FftPlanning planning = FftPlanning::Estimate);

// One line for `eulerfsi info`: the solver this build picks and its FFT library.
std::string poisson_backend_info();

}  // namespace eulerfsi
