#include "poisson/poisson_solver.hpp"

#include "kernels/projection.hpp"
#include "poisson/fft_dct_poisson.hpp"
#ifdef EULERFSI_HAVE_MPI
#include "poisson/fftw_mpi_poisson.hpp"
#endif

namespace eulerfsi {

PoissonSolver::~PoissonSolver() = default;

double PoissonSolver::solve_divergence(Field3 phi, const Field3& u, const Field3& v, const Field3& w, const double h[3],
                                       double scale, const Box& interior, const kernels::OpenFaceSum& flow) {
  const double open_sum = kernels::divergence(phi, u, v, w, h, scale, interior, flow);
  solve(phi);
  return open_sum;
}

namespace {
// CMake's EULERFSI_POISSON (AUTO picks FFT_DCT without MPI or on GPUs, FFTW_MPI otherwise)
#ifdef EULERFSI_POISSON_DEFAULT_FFT_DCT
constexpr bool kPreferFftDct = true;
#else
constexpr bool kPreferFftDct = false;
#endif
}  // namespace

std::unique_ptr<PoissonSolver> make_poisson_solver(const Grid& grid, MPI_Comm comm, FftPlanning planning) {
#ifdef EULERFSI_HAVE_MPI
  int size = 1;
  MPI_Comm_size(comm, &size);
  // FFT_DCT works on one rank only: a distributed run takes FFTW-MPI's transposes
  if (!kPreferFftDct || size > 1) return std::make_unique<FftwMpiPoisson>(grid, comm, planning);
#else
  (void)comm;
  (void)planning;
  static_assert(kPreferFftDct, "a build without MPI has only the FFT_DCT Poisson solver");
#endif
  return std::make_unique<FftDctPoisson>(grid);
}

std::string poisson_backend_info() {
  const std::string fft_dct = "fft-dct (one rank: r2c FFT + Makhoul DCT kernels, batched 1-D " +
                              make_fft_engine()->name() + ")";
#ifdef EULERFSI_HAVE_MPI
  const std::string fftw_mpi = std::string("fftw-mpi (distributed r2r via fftw3-mpi, ") + fftw_version + ")";
  return kPreferFftDct ? fft_dct + "; on several ranks " + fftw_mpi : fftw_mpi;
#else
  return fft_dct;
#endif
}

}  // namespace eulerfsi
