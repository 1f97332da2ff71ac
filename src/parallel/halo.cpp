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

}  // namespace eulerfsi
