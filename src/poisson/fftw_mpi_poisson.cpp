#include "poisson/fftw_mpi_poisson.hpp"

#include <stdexcept>

#include "kernels/projection.hpp"

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

// The divergence goes straight into the transform's contiguous unknowns (FFTW's own buffer on
// hosts): the gather pass of solve() is skipped, the arithmetic is the same.
double FftwMpiPoisson::solve_divergence(Field3 phi, const Field3& u, const Field3& v, const Field3& w,
                                        const double h[3], double scale, const Box& interior,
                                        const kernels::OpenFaceSum& flow) {
  // the block holds exactly the interior, shifted by kGhost: any other box would write past it
  const auto& block = transform_.unknown_block();
  for (int d = 0; d < 3; ++d)
    if (interior.lo[d] != kGhost || interior.hi[d] - interior.lo[d] != int(block.extent(d)))
      throw std::logic_error("FftwMpiPoisson::solve_divergence: the box is not this rank's interior");
  const double open_sum = kernels::divergence_shifted(transform_.unknown_block(), kGhost, u, v, w, h, scale, interior, flow);
  transform_.solve_gathered(phi, 0.0, 1.0);
  return open_sum;
}

}  // namespace eulerfsi
