#include "poisson/fftw_mpi_poisson.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/compat.hpp"
#include "poisson/fftw_threads.hpp"

namespace eulerfsi {

namespace {

// FFTW-MPI must be initialised once per process, after MPI_Init; cleanup is left to exit.
void ensure_fftw_mpi_init() {
  // a function-local static runs exactly once, even if two threads construct solvers
  static const bool done = [] {
    // the host threads Kokkos runs on also run the transforms (FFTW wants this before mpi_init)
    fftw_threads_once();
    fftw_mpi_init();
    return true;
  }();
  (void)done;
}

// Eigenvalues of (phi(i+1) - 2 phi(i) + phi(i-1)) / h^2 for the transform index m:
// periodic (R2HC) theta = 2 pi m / N, symmetric in m <-> N-m so the halfcomplex index works
// directly; wall (REDFT10) theta = pi m / N. 2(cos theta - 1) = -4 sin^2(theta/2), written
// the second way to avoid cancellation for the small modes that dominate phi.
Kokkos::View<double*, Kokkos::HostSpace> eigenvalues(int n, double h, Boundary bc, const char* label) {
  Kokkos::View<double*, Kokkos::HostSpace> lam(std::string(label), n);  // Kokkos 3.4 rejects const char* labels
  const double pi = 3.14159265358979323846;
  for (int m = 0; m < n; ++m) {
    const double theta = (bc == Boundary::Periodic ? 2.0 * pi : pi) * m / n;
    const double s = std::sin(0.5 * theta);
    lam(m) = -4.0 * s * s / (h * h);
  }
  return lam;
}

}  // namespace

FftwMpiPoisson::FftwMpiPoisson(const Grid& grid, MPI_Comm comm, Planning planning) {
  ensure_fftw_mpi_init();
  for (int d = 0; d < 3; ++d) n_[d] = grid.n[d];
  nx_local_ = grid.nx_local;

  ptrdiff_t local_n0 = 0, local_0_start = 0;
  const ptrdiff_t alloc_local = fftw_mpi_local_size_3d_transposed(n_[0], n_[1], n_[2], comm, &local_n0,
                                                                  &local_0_start, &local_n1_, &local_1_start_);
  // every rank must throw together: a rank that went on to plan would wait forever
  int mismatch = (local_n0 != grid.nx_local || local_0_start != grid.x_offset) ? 1 : 0;
  int any_mismatch = 0;
  MPI_Allreduce(&mismatch, &any_mismatch, 1, MPI_INT, MPI_MAX, comm);
  if (any_mismatch) {
    throw std::runtime_error("FftwMpiPoisson: FFTW-MPI distributes x as " + std::to_string(local_n0) +
                             " planes from " + std::to_string(local_0_start) + " on this rank, the grid as " +
                             std::to_string(grid.nx_local) + " from " + std::to_string(grid.x_offset) +
                             " (or another rank disagrees); build the Grid with the rank and size of this communicator");
  }

  buf_ = fftw_alloc_real(size_t(alloc_local > 0 ? alloc_local : 1));
  if (!buf_) throw std::runtime_error("FftwMpiPoisson: fftw_alloc_real failed");

  fftw_r2r_kind fwd[3], bwd[3];
  scale_ = 1.0;
  for (int d = 0; d < 3; ++d) {
    const bool periodic = grid.bc[d] == Boundary::Periodic;
    fwd[d] = periodic ? FFTW_R2HC : FFTW_REDFT10;
    bwd[d] = periodic ? FFTW_HC2R : FFTW_REDFT01;
    scale_ /= periodic ? double(n_[d]) : 2.0 * n_[d];
  }
  const unsigned effort = planning == Planning::Measure ? FFTW_MEASURE : FFTW_ESTIMATE;
#ifdef EULERFSI_FFTW_THREADS
  fftw_plan_with_nthreads(Kokkos::DefaultHostExecutionSpace().concurrency());
#endif
  forward_ = fftw_mpi_plan_r2r_3d(n_[0], n_[1], n_[2], buf_, buf_, comm, fwd[0], fwd[1], fwd[2],
                                  effort | FFTW_MPI_TRANSPOSED_OUT);
  backward_ = fftw_mpi_plan_r2r_3d(n_[0], n_[1], n_[2], buf_, buf_, comm, bwd[0], bwd[1], bwd[2],
                                   effort | FFTW_MPI_TRANSPOSED_IN);
  if (!forward_ || !backward_) {
    if (forward_) fftw_destroy_plan(forward_);
    if (backward_) fftw_destroy_plan(backward_);
    fftw_free(buf_);
    throw std::runtime_error("FftwMpiPoisson: FFTW-MPI could not plan the " + std::to_string(n_[0]) + "x" +
                             std::to_string(n_[1]) + "x" + std::to_string(n_[2]) + " r2r transform");
  }

  physical_ = HostBuffer3(buf_, nx_local_, n_[1], n_[2]);
  spectrum_ = HostBuffer3(buf_, size_t(local_n1_), n_[0], n_[2]);
  if (kHostAccessible) {
    // the kernels can write FFTW's buffer directly: no staging copy
    work_ = Work3(buf_, nx_local_, n_[1], n_[2]);
  } else {
    work_ = Work3(Kokkos::view_alloc(Kokkos::WithoutInitializing, "eulerfsi::poisson::work"), nx_local_, n_[1],
                  n_[2]);
  }
  const char* labels[3] = {"eulerfsi::poisson::lambda_x", "eulerfsi::poisson::lambda_y",
                           "eulerfsi::poisson::lambda_z"};
  for (int d = 0; d < 3; ++d) lambda_[d] = eigenvalues(n_[d], grid.h[d], grid.bc[d], labels[d]);
}

FftwMpiPoisson::~FftwMpiPoisson() {
  fftw_destroy_plan(forward_);
  fftw_destroy_plan(backward_);
  fftw_free(buf_);
}

void FftwMpiPoisson::solve(Field3 rhs_phi) {
  const int g = kGhost;
  Work3 work = work_;

  // gather: work(i,j,k) = f(i+g, j+g, k+g), the interior as one contiguous block for FFTW
  Kokkos::parallel_for(
      "eulerfsi::poisson::gather", Policy3({0, 0, 0}, {nx_local_, n_[1], n_[2]}),
      KOKKOS_LAMBDA(const int i, const int j, const int k) { work(i, j, k) = rhs_phi(i + g, j + g, k + g); });
  // FFTW reads the buffer from the host
  compat::fence();
  if (!kHostAccessible) Kokkos::deep_copy(physical_, work);

  fftw_execute(forward_);

  // hat(phi) = hat(f) / (lambda_x(i) + lambda_y(j) + lambda_z(k)) / (FFTW scale);
  // the zero mode (lambda = 0) is set to 0: it removes mean(f) and gives phi zero mean
  {
    HostBuffer3 spec = spectrum_;
    auto lx = lambda_[0], ly = lambda_[1], lz = lambda_[2];
    const int j0 = int(local_1_start_);
    const double scale = scale_;
    using HostPolicy3 = Kokkos::MDRangePolicy<Kokkos::DefaultHostExecutionSpace,
                                              Kokkos::Rank<3, Kokkos::Iterate::Right, Kokkos::Iterate::Right>>;
    Kokkos::parallel_for(
        "eulerfsi::poisson::divide_eigenvalues", HostPolicy3({0, 0, 0}, {int(local_n1_), n_[0], n_[2]}),
        [=](const int jl, const int i, const int k) {
          // transposed layout: (local y, global x, z)
          const double lam = lx(i) + ly(j0 + jl) + lz(k);
          spec(jl, i, k) = lam == 0.0 ? 0.0 : spec(jl, i, k) * (scale / lam);
        });
    Kokkos::DefaultHostExecutionSpace().fence();
  }

  fftw_execute(backward_);

  if (!kHostAccessible) Kokkos::deep_copy(work, physical_);
  // scatter: phi(i+g, j+g, k+g) = work(i,j,k); ghosts stay as they were (the caller fills them)
  Kokkos::parallel_for(
      "eulerfsi::poisson::scatter", Policy3({0, 0, 0}, {nx_local_, n_[1], n_[2]}),
      KOKKOS_LAMBDA(const int i, const int j, const int k) { rhs_phi(i + g, j + g, k + g) = work(i, j, k); });
  // no fence: the next solve fences before FFTW touches the buffer again
}

}  // namespace eulerfsi
