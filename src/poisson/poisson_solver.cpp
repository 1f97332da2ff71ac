#include "poisson/poisson_solver.hpp"

#include "poisson/fftw_mpi_poisson.hpp"

namespace eulerfsi {

PoissonSolver::~PoissonSolver() = default;

std::unique_ptr<PoissonSolver> make_poisson_solver(const Grid& grid, MPI_Comm comm) {
  return std::make_unique<FftwMpiPoisson>(grid, comm);
}

}  // namespace eulerfsi
