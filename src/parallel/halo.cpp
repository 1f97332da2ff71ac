#include "parallel/halo.hpp"

#include <climits>
#include <stdexcept>
#include <string>

#include "core/compat.hpp"

namespace eulerfsi {

namespace {
using Flat = Kokkos::View<double*, MemSpace, Kokkos::MemoryUnmanaged>;
using HostFlat = Kokkos::View<double*, Kokkos::HostSpace>;

#ifdef EULERFSI_GPU_AWARE_MPI
constexpr bool kMpiReadsMemSpace = true;
#else
constexpr bool kMpiReadsMemSpace = Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible;
#endif
// The x-halo between neighbouring ranks of a field whose storage holds the contiguous x-planes
// [a, b) of the slab (plane: cells per plane; the whole slab: a = 0, b = nx + 2 kGhost): the first
// owned planes go left (the left neighbour's right ghosts), the last owned go right, each cut to
// [a, b); both sides cut the same global planes when their windows cut one global window.
void exchange_planes(double* p, long plane, int a, int b, int nx, MPI_Comm comm, int rank, int size) {
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
  constexpr int kTagToLeft = 701, kTagToRight = 702;
  compat::fence();
  if (kMpiReadsMemSpace) {
    MPI_Sendrecv(p + send_left, n_send_left, MPI_DOUBLE, left, kTagToLeft, p + recv_right, n_recv_right, MPI_DOUBLE,
                 right, kTagToLeft, comm, MPI_STATUS_IGNORE);
    MPI_Sendrecv(p + send_right, n_send_right, MPI_DOUBLE, right, kTagToRight, p + recv_left, n_recv_left,
                 MPI_DOUBLE, left, kTagToRight, comm, MPI_STATUS_IGNORE);
    return;
  }
  // staging through host: contiguous plane ranges copy with one memcpy each way
  auto staged = [](const char* label, int n) {
    return HostFlat(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(label)), n);
  };
  HostFlat out_l = staged("eulerfsi::halo::out_l", n_send_left), in_r = staged("eulerfsi::halo::in_r", n_recv_right);
  HostFlat out_r = staged("eulerfsi::halo::out_r", n_send_right), in_l = staged("eulerfsi::halo::in_l", n_recv_left);
  Kokkos::deep_copy(out_l, Flat(p + send_left, n_send_left));
  Kokkos::deep_copy(out_r, Flat(p + send_right, n_send_right));
  MPI_Sendrecv(out_l.data(), n_send_left, MPI_DOUBLE, left, kTagToLeft, in_r.data(), n_recv_right, MPI_DOUBLE, right,
               kTagToLeft, comm, MPI_STATUS_IGNORE);
  MPI_Sendrecv(out_r.data(), n_send_right, MPI_DOUBLE, right, kTagToRight, in_l.data(), n_recv_left, MPI_DOUBLE, left,
               kTagToRight, comm, MPI_STATUS_IGNORE);
  Kokkos::deep_copy(Flat(p + recv_right, n_recv_right), in_r);
  Kokkos::deep_copy(Flat(p + recv_left, n_recv_left), in_l);
}

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

  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) {
    // one rank is its own neighbour: the periodic fill f(l) = f(l + nx), f(g + nx + l) = f(g + l)
    // for l < g, whole planes, as one kernel in MemSpace (no MPI, no host staging; the same values
    // the two self-messages of exchange_planes would copy)
    const int g = kGhost;
    Kokkos::parallel_for("eulerfsi::halo::periodic_x", Policy3({0, 0, 0}, {g, int(f.extent(1)), int(f.extent(2))}),
                         KOKKOS_LAMBDA(const int l, const int j, const int k) {
      f(l, j, k) = f(l + nx, j, k);
      f(g + nx + l, j, k) = f(g + l, j, k);
    });
    return;
  }
  exchange_planes(f.data(), plane, 0, nx + 2 * kGhost, nx, comm, rank, size);
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
  exchange_planes(f.data.data(), long(f.data.extent(1)) * long(f.data.extent(2)), a, b, nx, comm, rank, size);
}

}  // namespace eulerfsi
