#include "poisson/fftw_mpi_r2r.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/compat.hpp"
#include "poisson/fftw_threads.hpp"

namespace eulerfsi {

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

namespace {

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

// WisdomOnly asks for Measure's plan and takes it only from wisdom (null plans where there is none).
unsigned planning_flags(FftPlanning planning) {
  switch (planning) {
    case FftPlanning::Estimate: return FFTW_ESTIMATE;
    case FftPlanning::Measure: return FFTW_MEASURE;
    case FftPlanning::WisdomOnly: return FFTW_MEASURE | FFTW_WISDOM_ONLY;
  }
  return FFTW_ESTIMATE;
}

}  // namespace

bool FftwMpiR2r::use_tridiagonal(const Grid& grid, const R2rKind kind[3], AlongZ along_z) {
  return along_z == AlongZ::Tridiagonal && kind[2] != R2rKind::Periodic && unknowns(grid.n[2], kind[2]) <= kMaxLine;
}

namespace {

// FFTW-MPI's local sizes: of the 3-D transform, or of the 2-D x-y transform of n_z-tuples.
ptrdiff_t local_size(const int n[3], bool two_d, MPI_Comm comm, ptrdiff_t* n0, ptrdiff_t* s0, ptrdiff_t* n1,
                     ptrdiff_t* s1) {
  if (!two_d) return fftw_mpi_local_size_3d_transposed(n[0], n[1], n[2], comm, n0, s0, n1, s1);
  const ptrdiff_t nxy[2] = {n[0], n[1]};
  return fftw_mpi_local_size_many_transposed(2, nxy, n[2], FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, comm, n0, s0,
                                             n1, s1);
}

}  // namespace

size_t FftwMpiR2r::buffer_size(const Grid& grid, MPI_Comm comm, const R2rKind kind[3], AlongZ along_z) {
  ensure_fftw_mpi_init();
  const int n[3] = {unknowns(grid.n[0], kind[0]), unknowns(grid.n[1], kind[1]), unknowns(grid.n[2], kind[2])};
  ptrdiff_t n0, s0, n1, s1;
  const ptrdiff_t alloc = local_size(n, use_tridiagonal(grid, kind, along_z), comm, &n0, &s0, &n1, &s1);
  return size_t(alloc > 0 ? alloc : 1);
}

FftwMpiR2r::FftwMpiR2r(const Grid& grid, MPI_Comm comm, const R2rKind kind[3], Planning planning, const char* who,
                       double* shared, AlongZ along_z) {
  ensure_fftw_mpi_init();
  for (int d = 0; d < 3; ++d) n_[d] = unknowns(grid.n[d], kind[d]);
  nx_local_ = grid.nx_local;
  if (kind[0] == R2rKind::OddFace) throw std::runtime_error(std::string(who) + ": x is split across ranks: no OddFace");
  tridiagonal_z_ = use_tridiagonal(grid, kind, along_z);
  kind_z_ = kind[2];
  h_z_ = grid.h[2];

  ptrdiff_t local_n0 = 0, local_0_start = 0;
  const ptrdiff_t alloc_local = local_size(n_, tridiagonal_z_, comm, &local_n0, &local_0_start, &local_n1_, &local_1_start_);
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
  const int transformed = tridiagonal_z_ ? 2 : 3;
  for (int d = 0; d < 3; ++d) fftw_kinds(kind[d], fwd[d], bwd[d]);
  for (int d = 0; d < transformed; ++d) scale_ /= logical_size(n_[d], kind[d]);
  const unsigned effort = planning_flags(planning);
#ifdef EULERFSI_FFTW_THREADS
  fftw_plan_with_nthreads(Kokkos::DefaultHostExecutionSpace().concurrency());
#endif
  if (tridiagonal_z_) {
    // the x-y transform of each z-tuple: the tuples stay contiguous, so the transposes move lines
    const ptrdiff_t nxy[2] = {n_[0], n_[1]};
    forward_ = fftw_mpi_plan_many_r2r(2, nxy, n_[2], FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, buf_, buf_, comm,
                                      fwd, effort | FFTW_MPI_TRANSPOSED_OUT);
    backward_ = fftw_mpi_plan_many_r2r(2, nxy, n_[2], FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, buf_, buf_, comm,
                                       bwd, effort | FFTW_MPI_TRANSPOSED_IN);
  } else {
    forward_ = fftw_mpi_plan_r2r_3d(n_[0], n_[1], n_[2], buf_, buf_, comm, fwd[0], fwd[1], fwd[2],
                                    effort | FFTW_MPI_TRANSPOSED_OUT);
    backward_ = fftw_mpi_plan_r2r_3d(n_[0], n_[1], n_[2], buf_, buf_, comm, bwd[0], bwd[1], bwd[2],
                                     effort | FFTW_MPI_TRANSPOSED_IN);
  }
  if (!forward_ || !backward_) {
    if (forward_) fftw_destroy_plan(forward_);
    if (backward_) fftw_destroy_plan(backward_);
    if (owns_buffer_) fftw_free(buf_);
    throw std::runtime_error(std::string(who) + ": FFTW-MPI could not plan the " + std::to_string(n_[0]) + "x" +
                             std::to_string(n_[1]) + "x" + std::to_string(n_[2]) + " r2r transform" +
                             (planning == Planning::WisdomOnly ? " from the imported wisdom alone" : ""));
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
  solve_gathered(f, a, b);
}

void FftwMpiR2r::solve_gathered(const Field3& f, double a, double b) {
  const int g = kGhost;
  Work3 work = work_;
  const Field3 field = f;
  // FFTW reads the buffer from the host
  compat::fence();
  if (!kHostAccessible) Kokkos::deep_copy(physical_, work);

  fftw_execute(forward_);

  if (tridiagonal_z_)
    solve_z_lines(a, b);
  else
    divide_eigenvalues(a, b);

  fftw_execute(backward_);

  if (!kHostAccessible) Kokkos::deep_copy(work, physical_);
  // scatter: x(i+g, j+g, k+g) = work(i,j,k); ghosts stay as they were (the caller fills them)
  Kokkos::parallel_for(
      "eulerfsi::fft::scatter", Policy3({0, 0, 0}, {nx_local_, n_[1], n_[2]}),
      KOKKOS_LAMBDA(const int i, const int j, const int k) { field(i + g, j + g, k + g) = work(i, j, k); });
  // no fence: the next solve fences before FFTW touches the buffer again
}

namespace {
using HostPolicy2 = Kokkos::MDRangePolicy<Kokkos::DefaultHostExecutionSpace,
                                          Kokkos::Rank<2, Kokkos::Iterate::Right, Kokkos::Iterate::Right>>;
using HostPolicy3 = Kokkos::MDRangePolicy<Kokkos::DefaultHostExecutionSpace,
                                          Kokkos::Rank<3, Kokkos::Iterate::Right, Kokkos::Iterate::Right>>;
constexpr int kLinesPerBlock = 8;  // z lines solved together: their divisions overlap
}  // namespace

// hat(x) = hat(f) / (a + b (lambda_x(i) + lambda_y(j) + lambda_z(k))) / (FFTW's scale)
void FftwMpiR2r::divide_eigenvalues(double a, double b) {
  HostBuffer3 spec = spectrum_;
  auto lx = lambda_[0], ly = lambda_[1], lz = lambda_[2];
  const int j0 = int(local_1_start_);
  const double scale = scale_;
  Kokkos::parallel_for(
      "eulerfsi::fft::divide_eigenvalues", HostPolicy3({0, 0, 0}, {int(local_n1_), n_[0], n_[2]}),
      [=](const int jl, const int i, const int k) {
        // transposed layout: (local y, global x, z)
        const double den = a + b * (lx(i) + ly(j0 + jl) + lz(k));
        spec(jl, i, k) = den == 0.0 ? 0.0 : spec(jl, i, k) * (scale / den);
      });
  Kokkos::DefaultHostExecutionSpace().fence();
}

// Each z line of the x-y spectrum (Thomas algorithm, eight lines at once):
//   e x_(k-1) + (c - 2 e) x_k + e x_(k+1) = scale f_k,   c = a + b (lambda_x + lambda_y),  e = b / h_z^2
// with the end rule of the z kind: EvenHalf x_(-1) = x_0 (diagonal c - e at the ends), OddHalf
// x_(-1) = -x_0 (c - 3 e), OddFace x_(-1) = x_n = 0 (c - 2 e). Diagonally dominant for a b <= 0 or
// a = 0: no pivoting. The one singular line (a = 0, EvenHalf, lambda_x + lambda_y = 0: the Poisson
// zero mode) is integrated twice from its flux, f minus its mean, and given zero mean, which is what
// setting the zero mode to 0 does in the transform.
void FftwMpiR2r::solve_z_lines(double a, double b) {
  HostBuffer3 spec = spectrum_;
  auto lx = lambda_[0], ly = lambda_[1];
  const int j0 = int(local_1_start_), nx = n_[0], nz = n_[2];
  const double scale = scale_, e = b / (h_z_ * h_z_);
  // the diagonal of an end row is c + end
  const double end = kind_z_ == R2rKind::EvenHalf ? -e : (kind_z_ == R2rKind::OddHalf ? -3.0 * e : -2.0 * e);
  const bool zero_mode_possible = a == 0.0 && kind_z_ == R2rKind::EvenHalf;
  const int blocks = (nx + kLinesPerBlock - 1) / kLinesPerBlock;
  Kokkos::parallel_for(
      "eulerfsi::fft::tridiagonal_z", HostPolicy2({0, 0}, {int(local_n1_), blocks}), [=](const int jl, const int blk) {
        constexpr int W = kLinesPerBlock;
        double cp[kMaxLine][W];  // the eliminated super-diagonal of each line
        const int i0 = blk * W, lanes = nx - i0 < W ? nx - i0 : W;
        double c[W], y[W];
        int singular = -1;
        for (int l = 0; l < lanes; ++l) {
          c[l] = a + b * (lx(i0 + l) + ly(j0 + jl));
          // the zero-mode line: solved below; any regular diagonal keeps the block's sweep finite
          if (zero_mode_possible && c[l] == 0.0) singular = l, c[l] = -e;
        }
        double zero_mode[kMaxLine];
        if (singular >= 0) {
          double mean = 0.0;
          for (int k = 0; k < nz; ++k) mean += spec(jl, i0 + singular, k);
          mean /= nz;
          double flux = 0.0, x = 0.0, sum = 0.0;
          for (int k = 0; k < nz; ++k) {
            zero_mode[k] = x;
            sum += x;
            flux += scale * (spec(jl, i0 + singular, k) - mean);
            x += flux / e;
          }
          for (int k = 0; k < nz; ++k) zero_mode[k] -= sum / nz;
        }
        if (nz == 1) {
          for (int l = 0; l < lanes; ++l) {
            const double d = c[l] + 2.0 * end + 2.0 * e;  // both end rules on the one cell
            spec(jl, i0 + l, 0) = d == 0.0 ? 0.0 : scale * spec(jl, i0 + l, 0) / d;
          }
        } else {
          for (int l = 0; l < lanes; ++l) {
            const double inv = 1.0 / (c[l] + end);
            cp[0][l] = e * inv;
            y[l] = scale * spec(jl, i0 + l, 0) * inv;
            spec(jl, i0 + l, 0) = y[l];
          }
          for (int k = 1; k < nz; ++k) {
            const double diag_add = k == nz - 1 ? end : -2.0 * e;
            for (int l = 0; l < lanes; ++l) {
              const double inv = 1.0 / (c[l] + diag_add - e * cp[k - 1][l]);
              cp[k][l] = e * inv;
              y[l] = (scale * spec(jl, i0 + l, k) - e * y[l]) * inv;
              spec(jl, i0 + l, k) = y[l];
            }
          }
          for (int k = nz - 2; k >= 0; --k)
            for (int l = 0; l < lanes; ++l) spec(jl, i0 + l, k) -= cp[k][l] * spec(jl, i0 + l, k + 1);
        }
        if (singular >= 0)
          for (int k = 0; k < nz; ++k) spec(jl, i0 + singular, k) = zero_mode[k];
      });
  Kokkos::DefaultHostExecutionSpace().fence();
}

}  // namespace eulerfsi
