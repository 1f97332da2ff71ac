#include "parallel/halo.hpp"

#include <climits>
#include <stdexcept>
#include <string>

#include "core/compat.hpp"

namespace eulerfsi {

namespace {
using Slab = Kokkos::View<double***, Kokkos::LayoutRight, MemSpace, Kokkos::MemoryUnmanaged>;
using HostSlab = Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace>;

#ifdef EULERFSI_GPU_AWARE_MPI
constexpr bool kMpiReadsMemSpace = true;
#else
constexpr bool kMpiReadsMemSpace = Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible;
#endif
}  // namespace

void exchange_x(Field3 f, const Grid& g, MPI_Comm comm) {
  const int nx = g.nx_local;
  if (int(f.extent(0)) != nx + 2 * kGhost) {
    throw std::invalid_argument("exchange_x: field has " + std::to_string(f.extent(0)) + " x-planes, grid needs " +
                                std::to_string(nx + 2 * kGhost));
  }
  const long plane = long(f.extent(1)) * long(f.extent(2));
  // whole x-planes are contiguous only in an unpadded LayoutRight allocation
  if (!f.span_is_contiguous() || long(f.stride(0)) != plane) {
    throw std::invalid_argument("exchange_x: field x-planes are not contiguous");
  }
  const long count_l = kGhost * plane;
  if (count_l > INT_MAX) throw std::invalid_argument("exchange_x: ghost slab too large for one MPI message");
  const int count = int(count_l);

  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) {
    // one rank is its own neighbour: the periodic fill f(l) = f(l + nx), f(g + nx + l) = f(g + l)
    // for l < g, whole planes, as one kernel in MemSpace (no MPI, no host staging; the same values
    // the two self-messages below would copy)
    const int g = kGhost;
    Kokkos::parallel_for("eulerfsi::halo::periodic_x", Policy3({0, 0, 0}, {g, int(f.extent(1)), int(f.extent(2))}),
                         KOKKOS_LAMBDA(const int l, const int j, const int k) {
      f(l, j, k) = f(l + nx, j, k);
      f(g + nx + l, j, k) = f(g + l, j, k);
    });
    return;
  }
  const int left = (rank - 1 + size) % size;
  const int right = (rank + 1) % size;
  // first owned planes go left (they are the left neighbour's right ghosts), last owned go right
  const long send_left = kGhost * plane, recv_right = long(kGhost + nx) * plane;
  const long send_right = long(nx) * plane, recv_left = 0;
  constexpr int kTagToLeft = 701, kTagToRight = 702;

  compat::fence();
  double* p = f.data();
  if (kMpiReadsMemSpace) {
    MPI_Sendrecv(p + send_left, count, MPI_DOUBLE, left, kTagToLeft, p + recv_right, count, MPI_DOUBLE, right,
                 kTagToLeft, comm, MPI_STATUS_IGNORE);
    MPI_Sendrecv(p + send_right, count, MPI_DOUBLE, right, kTagToRight, p + recv_left, count, MPI_DOUBLE, left,
                 kTagToRight, comm, MPI_STATUS_IGNORE);
    return;
  }
  // staging through host: contiguous slabs copy with one memcpy each way
  const int ny = int(f.extent(1)), nz = int(f.extent(2));
  auto slab = [p, ny, nz](long off) { return Slab(p + off, kGhost, ny, nz); };
  HostSlab out_l(Kokkos::view_alloc(Kokkos::WithoutInitializing, "eulerfsi::halo::out_l"), kGhost, ny, nz);
  HostSlab out_r(Kokkos::view_alloc(Kokkos::WithoutInitializing, "eulerfsi::halo::out_r"), kGhost, ny, nz);
  HostSlab in_l(Kokkos::view_alloc(Kokkos::WithoutInitializing, "eulerfsi::halo::in_l"), kGhost, ny, nz);
  HostSlab in_r(Kokkos::view_alloc(Kokkos::WithoutInitializing, "eulerfsi::halo::in_r"), kGhost, ny, nz);
  Kokkos::deep_copy(out_l, slab(send_left));
  Kokkos::deep_copy(out_r, slab(send_right));
  MPI_Sendrecv(out_l.data(), count, MPI_DOUBLE, left, kTagToLeft, in_r.data(), count, MPI_DOUBLE, right, kTagToLeft,
               comm, MPI_STATUS_IGNORE);
  MPI_Sendrecv(out_r.data(), count, MPI_DOUBLE, right, kTagToRight, in_l.data(), count, MPI_DOUBLE, left,
               kTagToRight, comm, MPI_STATUS_IGNORE);
  Kokkos::deep_copy(slab(recv_right), in_r);
  Kokkos::deep_copy(slab(recv_left), in_l);
}

void exchange_x(const WindowField& f, const Grid& g, MPI_Comm comm) {
  const int nx = g.nx_local, a = f.lo[0], b = f.lo[0] + int(f.data.extent(0));
  if (a == 0 && b == nx + 2 * kGhost) {  // every plane: the whole-slab exchange
    exchange_x(f.data, g, comm);
    return;
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) {
    if (a < kGhost || b > nx + kGhost)
      throw std::logic_error("exchange_x: a window holding an x-ghost plane on one rank must hold every plane");
    return;  // no ghost plane in the window: nothing to fill
  }
  const long plane = long(f.data.extent(1)) * long(f.data.extent(2));
  // [lo, hi) of storage planes cut to the window, as an offset into its data and a count
  auto cut = [a, b, plane](int lo, int hi, long& offset, int& count) {
    lo = lo > a ? lo : a;
    hi = hi < b ? hi : b;
    offset = long(lo - a) * plane;
    const long n = hi > lo ? long(hi - lo) * plane : 0;
    if (n > INT_MAX) throw std::invalid_argument("exchange_x: ghost slab too large for one MPI message");
    count = int(n);
  };
  long send_left, recv_right, send_right, recv_left;
  int n_send_left, n_recv_right, n_send_right, n_recv_left;
  cut(kGhost, 2 * kGhost, send_left, n_send_left);
  cut(kGhost + nx, 2 * kGhost + nx, recv_right, n_recv_right);
  cut(nx, nx + kGhost, send_right, n_send_right);
  cut(0, kGhost, recv_left, n_recv_left);
  const int left = (rank - 1 + size) % size, right = (rank + 1) % size;
  constexpr int kTagToLeft = 703, kTagToRight = 704;
  compat::fence();
  double* p = f.data.data();
  if (kMpiReadsMemSpace) {
    MPI_Sendrecv(p + send_left, n_send_left, MPI_DOUBLE, left, kTagToLeft, p + recv_right, n_recv_right, MPI_DOUBLE,
                 right, kTagToLeft, comm, MPI_STATUS_IGNORE);
    MPI_Sendrecv(p + send_right, n_send_right, MPI_DOUBLE, right, kTagToRight, p + recv_left, n_recv_left,
                 MPI_DOUBLE, left, kTagToRight, comm, MPI_STATUS_IGNORE);
    return;
  }
  using Flat = Kokkos::View<double*, MemSpace, Kokkos::MemoryUnmanaged>;
  using HostFlat = Kokkos::View<double*, Kokkos::HostSpace>;
  auto staged = [](const char* label, int n) { return HostFlat(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(label)), n); };
  HostFlat out_l = staged("eulerfsi::halo::window_out_l", n_send_left), in_r = staged("eulerfsi::halo::window_in_r", n_recv_right);
  HostFlat out_r = staged("eulerfsi::halo::window_out_r", n_send_right), in_l = staged("eulerfsi::halo::window_in_l", n_recv_left);
  Kokkos::deep_copy(out_l, Flat(p + send_left, n_send_left));
  Kokkos::deep_copy(out_r, Flat(p + send_right, n_send_right));
  MPI_Sendrecv(out_l.data(), n_send_left, MPI_DOUBLE, left, kTagToLeft, in_r.data(), n_recv_right, MPI_DOUBLE, right,
               kTagToLeft, comm, MPI_STATUS_IGNORE);
  MPI_Sendrecv(out_r.data(), n_send_right, MPI_DOUBLE, right, kTagToRight, in_l.data(), n_recv_left, MPI_DOUBLE, left,
               kTagToRight, comm, MPI_STATUS_IGNORE);
  Kokkos::deep_copy(Flat(p + recv_right, n_recv_right), in_r);
  Kokkos::deep_copy(Flat(p + recv_left, n_recv_left), in_l);
}

}  // namespace eulerfsi
