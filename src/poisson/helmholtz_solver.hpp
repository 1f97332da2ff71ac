#pragma once
// The implicit part of the viscous term (time.implicit_viscosity): for one velocity component on
// the MAC grid,
//   (I - c L_h) x = f,   L_h the 7-point Laplacian with that component's no-slip rule at walls,
// homogeneous: a tangential component has x(-1) = -x(0) (zero on the wall, half a cell out), the
// wall-normal one lives on the faces and is zero on the wall faces. The wall's own velocity enters
// the right-hand side (FlowSolver). Solved exactly by fast transforms, like the pressure.
#include <memory>

#include "core/types.hpp"
#include "grid/grid.hpp"
#include "parallel/mpi.hpp"
#include "poisson/fft_planning.hpp"

namespace eulerfsi {

class HelmholtzSolver {
 public:
  virtual ~HelmholtzSolver();
  // Overwrites component `component`'s unknowns in f (storage kGhost + [0, n); along a wall
  // direction the wall-normal component stops one face short: its last face is the wall) with x.
  virtual void solve(int component, const Field3& f, double c) = 0;
};

// FFTW-MPI on x-slabs; throws std::runtime_error in a build without MPI.
std::unique_ptr<HelmholtzSolver> make_helmholtz_solver(const Grid& grid, MPI_Comm comm,
                                                       FftPlanning planning = FftPlanning::Estimate);

}  // namespace eulerfsi
