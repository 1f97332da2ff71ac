#pragma once
// Exact 7-point Poisson solve with FFTW-MPI's distributed real-to-real transforms on x-slabs.
//
// One 3-D r2r transform diagonalises L_h: R2HC (real DFT) along periodic directions,
// REDFT10 (DCT-II) along wall directions, whose discrete Neumann condition phi(-1) = phi(0)
// is exactly the even extension about the wall that DCT-II assumes (poisson/fftw_mpi_r2r.hpp).
#include "poisson/fftw_mpi_r2r.hpp"
#include "poisson/poisson_solver.hpp"

namespace eulerfsi {

class FftwMpiPoisson final : public PoissonSolver {
 public:
  using Planning = FftwMpiR2r::Planning;

  FftwMpiPoisson(const Grid& grid, MPI_Comm comm, Planning planning = Planning::Estimate);

  void solve(Field3 rhs_phi) override { transform_.solve(rhs_phi, 0.0, 1.0); }
  double solve_divergence(Field3 phi, const Field3& u, const Field3& v, const Field3& w, const double h[3],
                          double scale, const Box& interior, const kernels::OpenFaceSum& flow = {}) override;
  const char* name() const override { return "fftw-mpi"; }

 private:
  FftwMpiR2r transform_;
};

}  // namespace eulerfsi
