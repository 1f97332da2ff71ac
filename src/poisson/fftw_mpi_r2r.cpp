#include "poisson/fftw_mpi_r2r.hpp"

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

// The transform sizes: one unknown less along an OddFace direction (its last face is the wall).
int unknowns(int cells, R2rKind kind) { return kind == R2rKind::OddFace ? cells - 1 : cells; }

// lambda_m = -4 sin^2(theta_m / 2) / h^2 for the m-th basis function of `kind` (header).
Kokkos::View<double*, Kokkos::HostSpace> eigenvalues(int cells, double h, R2rKind kind, const char* label) {
  const int n = unknowns(cells, kind);
  Kokkos::View<double*, Kokkos::HostSpace> lam(std::string(label), n);  // Kokkos 3.4 rejects const char* labels
  const double pi = 3.14159265358979323846;
  for (int m = 0; m < n; ++m) {
    double theta = 0.0;
    switch (kind) {
      case R2rKind::Periodic: theta = 2.0 * pi * m / cells; break;
      case R2rKind::EvenHalf: theta = pi * m / cells; break;
      case R2rKind::OddHalf:
      case R2rKind::OddFace: theta = pi * (m + 1) / cells; break;
    }
    const double s = std::sin(0.5 * theta);
    lam(m) = -4.0 * s * s / (h * h);
  }
  return lam;
}

void fftw_kinds(R2rKind kind, fftw_r2r_kind& forward, fftw_r2r_kind& backward) {
  switch (kind) {
    case R2rKind::Periodic: forward = FFTW_R2HC, backward = FFTW_HC2R; return;
    case R2rKind::EvenHalf: forward = FFTW_REDFT10, backward = FFTW_REDFT01; return;
    case R2rKind::OddHalf: forward = FFTW_RODFT10, backward = FFTW_RODFT01; return;
    case R2rKind::OddFace: forward = backward = FFTW_RODFT00; return;
  }
}

// The logical size N of a forward-backward pair (FFTW returns N x): n, 2n, 2n, 2(n + 1).
double logical_size(int n, R2rKind kind) {
  switch (kind) {
    case R2rKind::Periodic: return n;
    case R2rKind::EvenHalf:
    case R2rKind::OddHalf: return 2.0 * n;
    case R2rKind::OddFace: return 2.0 * (n + 1);
  }
  return n;
}

}  // namespace

size_t FftwMpiR2r::buffer_size(const Grid& grid, MPI_Comm comm, const R2rKind kind[3]) {
  ensure_fftw_mpi_init();
  ptrdiff_t n0, s0, n1, s1;
  const ptrdiff_t alloc = fftw_mpi_local_size_3d_transposed(unknowns(grid.n[0], kind[0]), unknowns(grid.n[1], kind[1]),
                                                            unknowns(grid.n[2], kind[2]), comm, &n0, &s0, &n1, &s1);
  return size_t(alloc > 0 ? alloc : 1);
}

FftwMpiR2r::FftwMpiR2r(const Grid& grid, MPI_Comm comm, const R2rKind kind[3], Planning planning, const char* who,
                       double* shared) {
  ensure_fftw_mpi_init();
  for (int d = 0; d < 3; ++d) n_[d] = unknowns(grid.n[d], kind[d]);
  nx_local_ = grid.nx_local;
  if (kind[0] == R2rKind::OddFace) throw std::runtime_error(std::string(who) + ": x is split across ranks: no OddFace");

  ptrdiff_t local_n0 = 0, local_0_start = 0;
  const ptrdiff_t alloc_local = fftw_mpi_local_size_3d_transposed(n_[0], n_[1], n_[2], comm, &local_n0,
                                                                  &local_0_start, &local_n1_, &local_1_start_);
  // every rank must throw together: a rank that went on to plan would wait forever
  int mismatch = (local_n0 != grid.nx_local || local_0_start != grid.x_offset) ? 1 : 0;
  int any_mismatch = 0;
  MPI_Allreduce(&mismatch, &any_mismatch, 1, MPI_INT, MPI_MAX, comm);
  if (any_mismatch) {
    throw std::runtime_error(std::string(who) + ": FFTW-MPI distributes x as " + std::to_string(local_n0) +
                             " planes from " + std::to_string(local_0_start) + " on this rank, the grid as " +
                             std::to_string(grid.nx_local) + " from " + std::to_string(grid.x_offset) +
                             " (or another rank disagrees); build the Grid with the rank and size of this communicator");
  }

  owns_buffer_ = shared == nullptr;
  buf_ = shared ? shared : fftw_alloc_real(size_t(alloc_local > 0 ? alloc_local : 1));
  if (!buf_) throw std::runtime_error(std::string(who) + ": fftw_alloc_real failed");

  fftw_r2r_kind fwd[3], bwd[3];
  scale_ = 1.0;
  for (int d = 0; d < 3; ++d) {
    fftw_kinds(kind[d], fwd[d], bwd[d]);
    scale_ /= logical_size(n_[d], kind[d]);
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
    if (owns_buffer_) fftw_free(buf_);
    throw std::runtime_error(std::string(who) + ": FFTW-MPI could not plan the " + std::to_string(n_[0]) + "x" +
                             std::to_string(n_[1]) + "x" + std::to_string(n_[2]) + " r2r transform");
  }

  physical_ = HostBuffer3(buf_, nx_local_, n_[1], n_[2]);
  spectrum_ = HostBuffer3(buf_, size_t(local_n1_), n_[0], n_[2]);
  if (kHostAccessible) {
    // the kernels can write FFTW's buffer directly: no staging copy
    work_ = Work3(buf_, nx_local_, n_[1], n_[2]);
  } else {
    work_ = Work3(Kokkos::view_alloc(Kokkos::WithoutInitializing, "eulerfsi::fft::work"), nx_local_, n_[1], n_[2]);
  }
  const char* labels[3] = {"eulerfsi::fft::lambda_x", "eulerfsi::fft::lambda_y", "eulerfsi::fft::lambda_z"};
  for (int d = 0; d < 3; ++d) lambda_[d] = eigenvalues(grid.n[d], grid.h[d], kind[d], labels[d]);
}

FftwMpiR2r::~FftwMpiR2r() {
  fftw_destroy_plan(forward_);
  fftw_destroy_plan(backward_);
  if (owns_buffer_) fftw_free(buf_);
}

void FftwMpiR2r::solve(const Field3& f, double a, double b) {
  const int g = kGhost;
  Work3 work = work_;
  const Field3 field = f;

  // gather: work(i,j,k) = f(i+g, j+g, k+g), the unknowns as one contiguous block for FFTW
  Kokkos::parallel_for(
      "eulerfsi::fft::gather", Policy3({0, 0, 0}, {nx_local_, n_[1], n_[2]}),
      KOKKOS_LAMBDA(const int i, const int j, const int k) { work(i, j, k) = field(i + g, j + g, k + g); });
  // FFTW reads the buffer from the host
  compat::fence();
  if (!kHostAccessible) Kokkos::deep_copy(physical_, work);

  fftw_execute(forward_);

  // hat(x) = hat(f) / (a + b (lambda_x(i) + lambda_y(j) + lambda_z(k))) / (FFTW's scale)
  {
    HostBuffer3 spec = spectrum_;
    auto lx = lambda_[0], ly = lambda_[1], lz = lambda_[2];
    const int j0 = int(local_1_start_);
    const double scale = scale_;
    using HostPolicy3 = Kokkos::MDRangePolicy<Kokkos::DefaultHostExecutionSpace,
                                              Kokkos::Rank<3, Kokkos::Iterate::Right, Kokkos::Iterate::Right>>;
    Kokkos::parallel_for(
        "eulerfsi::fft::divide_eigenvalues", HostPolicy3({0, 0, 0}, {int(local_n1_), n_[0], n_[2]}),
        [=](const int jl, const int i, const int k) {
          // transposed layout: (local y, global x, z)
          const double den = a + b * (lx(i) + ly(j0 + jl) + lz(k));
          spec(jl, i, k) = den == 0.0 ? 0.0 : spec(jl, i, k) * (scale / den);
        });
    Kokkos::DefaultHostExecutionSpace().fence();
  }

  fftw_execute(backward_);

  if (!kHostAccessible) Kokkos::deep_copy(work, physical_);
  // scatter: x(i+g, j+g, k+g) = work(i,j,k); ghosts stay as they were (the caller fills them)
  Kokkos::parallel_for(
      "eulerfsi::fft::scatter", Policy3({0, 0, 0}, {nx_local_, n_[1], n_[2]}),
      KOKKOS_LAMBDA(const int i, const int j, const int k) { field(i + g, j + g, k + g) = work(i, j, k); });
  // no fence: the next solve fences before FFTW touches the buffer again
}

}  // namespace eulerfsi
