#include "poisson/helmholtz_solver.hpp"

#include <algorithm>
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
// The three run one after the other and share one buffer.
class FftwMpiHelmholtz final : public HelmholtzSolver {
 public:
  FftwMpiHelmholtz(const Grid& grid, MPI_Comm comm, FftPlanning planning) {
    R2rKind kind[3][3];
    size_t size = 0;
    for (int c = 0; c < 3; ++c) {
      for (int d = 0; d < 3; ++d)
        kind[c][d] = grid.bc[d] == Boundary::Periodic ? R2rKind::Periodic : (d == c ? R2rKind::OddFace : R2rKind::OddHalf);
      size = std::max(size, FftwMpiR2r::buffer_size(grid, comm, kind[c]));
    }
    buffer_ = fftw_alloc_real(size);
    if (!buffer_) throw std::runtime_error("FftwMpiHelmholtz: fftw_alloc_real failed");
    for (int c = 0; c < 3; ++c)
      transform_[c] = std::make_unique<FftwMpiR2r>(grid, comm, kind[c], planning, "FftwMpiHelmholtz", buffer_);
  }
  ~FftwMpiHelmholtz() override {
    for (auto& t : transform_) t.reset();  // the plans before the buffer they run on
    fftw_free(buffer_);
  }
  FftwMpiHelmholtz(const FftwMpiHelmholtz&) = delete;
  FftwMpiHelmholtz& operator=(const FftwMpiHelmholtz&) = delete;
  void solve(int component, const Field3& f, double c) override { transform_[component]->solve(f, 1.0, -c); }

 private:
  double* buffer_ = nullptr;
  std::unique_ptr<FftwMpiR2r> transform_[3];
};

}  // namespace

std::unique_ptr<HelmholtzSolver> make_helmholtz_solver(const Grid& grid, MPI_Comm comm, FftPlanning planning) {
  return std::make_unique<FftwMpiHelmholtz>(grid, comm, planning);
}
#else
std::unique_ptr<HelmholtzSolver> make_helmholtz_solver(const Grid&, MPI_Comm, FftPlanning) {
  throw std::runtime_error(
      "time.implicit_viscosity = true needs the FFTW-MPI transforms, and this build has no MPI "
      "(configure with -DEULERFSI_ENABLE_MPI=ON)");
}
#endif

}  // namespace eulerfsi
