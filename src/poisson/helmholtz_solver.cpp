#include "poisson/helmholtz_solver.hpp"

#include <stdexcept>

#ifdef EULERFSI_HAVE_MPI
#include "poisson/fftw_mpi_r2r.hpp"
#endif

namespace eulerfsi {

HelmholtzSolver::~HelmholtzSolver() = default;

#ifdef EULERFSI_HAVE_MPI
namespace {

// One transform per component: along a wall direction DST-I on the faces for the component
// normal to it, DST-II on the cell centres for the two tangential ones; periodic: the real DFT.
class FftwMpiHelmholtz final : public HelmholtzSolver {
 public:
  FftwMpiHelmholtz(const Grid& grid, MPI_Comm comm) {
    for (int c = 0; c < 3; ++c) {
      R2rKind kind[3];
      for (int d = 0; d < 3; ++d)
        kind[d] = grid.bc[d] == Boundary::Periodic ? R2rKind::Periodic : (d == c ? R2rKind::OddFace : R2rKind::OddHalf);
      transform_[c] = std::make_unique<FftwMpiR2r>(grid, comm, kind, FftwMpiR2r::Planning::Estimate, "FftwMpiHelmholtz");
    }
  }
  void solve(int component, const Field3& f, double c) override { transform_[component]->solve(f, 1.0, -c); }

 private:
  std::unique_ptr<FftwMpiR2r> transform_[3];
};

}  // namespace

std::unique_ptr<HelmholtzSolver> make_helmholtz_solver(const Grid& grid, MPI_Comm comm) {
  return std::make_unique<FftwMpiHelmholtz>(grid, comm);
}
#else
std::unique_ptr<HelmholtzSolver> make_helmholtz_solver(const Grid&, MPI_Comm) {
  throw std::runtime_error(
      "time.implicit_viscosity = true needs the FFTW-MPI transforms, and this build has no MPI "
      "(configure with -DEULERFSI_ENABLE_MPI=ON)");
}
#endif

}  // namespace eulerfsi
