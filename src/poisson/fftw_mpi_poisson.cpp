#include "poisson/fftw_mpi_poisson.hpp"

namespace eulerfsi {

namespace {

// Periodic directions by the real DFT, walls by DCT-II (the pressure's Neumann rule).
struct PressureKinds {
  R2rKind kind[3];
  explicit PressureKinds(const Grid& g) {
    for (int d = 0; d < 3; ++d) kind[d] = g.bc[d] == Boundary::Periodic ? R2rKind::Periodic : R2rKind::EvenHalf;
  }
};

}  // namespace

FftwMpiPoisson::FftwMpiPoisson(const Grid& grid, MPI_Comm comm, Planning planning)
    : transform_(grid, comm, PressureKinds(grid).kind, planning, "FftwMpiPoisson") {}

}  // namespace eulerfsi
