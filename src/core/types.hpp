#pragma once
// Field storage and iteration policies shared by kernels and driver.
#include <Kokkos_Core.hpp>

namespace eulerfsi {

using ExecSpace = Kokkos::DefaultExecutionSpace;
using MemSpace = ExecSpace::memory_space;

// A scalar field on the local slab with ghost layers; k (z) is contiguous on every backend.
using Field3 = Kokkos::View<double***, Kokkos::LayoutRight, MemSpace>;
using ConstField3 = Kokkos::View<const double***, Kokkos::LayoutRight, MemSpace>;
using HostField3 = Field3::HostMirror;
using Line = Kokkos::View<double*, MemSpace>;

// The same iteration order on CPU and GPU: k fastest.
using Policy3 = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3, Kokkos::Iterate::Right, Kokkos::Iterate::Right>>;
using Policy2 = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2, Kokkos::Iterate::Right, Kokkos::Iterate::Right>>;

// Ghost layers on every side: WENO5 reads three cells upwind.
constexpr int kGhost = 3;

// Index box [lo, hi) in storage indices (ghosts included in the numbering).
struct Box {
  int lo[3];
  int hi[3];
  Policy3 policy() const {
    // an empty range must be clamped: Kokkos 4.3+ aborts on hi < lo
    const int h0 = hi[0] > lo[0] ? hi[0] : lo[0], h1 = hi[1] > lo[1] ? hi[1] : lo[1], h2 = hi[2] > lo[2] ? hi[2] : lo[2];
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP)
    // GPUs: Kokkos puts the first index on threadIdx.x (its default tiles make a warp read four
    // 64-byte pieces), so tiles one cell deep in i and up to 64 cells along the contiguous k give
    // 128-byte runs; 128 threads a block. Not yet timed on a GPU.
    int tk = 1;
    while (tk < 64 && tk < h2 - lo[2]) tk *= 2;
    return Policy3({lo[0], lo[1], lo[2]}, {h0, h1, h2}, {1, 128 / tk, tk});
#else
    return Policy3({lo[0], lo[1], lo[2]}, {h0, h1, h2});
#endif
  }
  long size() const {
    long n = 1;
    for (int d = 0; d < 3; ++d) n *= (hi[d] > lo[d] ? hi[d] - lo[d] : 0);
    return n;
  }
  bool empty() const { return size() == 0; }
  // This box grown by `by` cells on every side, cut to `limit` (empty stays empty).
  Box grown(int by, const Box& limit) const {
    if (empty()) return *this;
    Box g;
    for (int d = 0; d < 3; ++d) {
      g.lo[d] = lo[d] - by > limit.lo[d] ? lo[d] - by : limit.lo[d];
      g.hi[d] = hi[d] + by < limit.hi[d] ? hi[d] + by : limit.hi[d];
    }
    return g;
  }
};

// The smallest box holding both (an empty box holds nothing).
inline Box bounding_box(const Box& a, const Box& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  Box u;
  for (int d = 0; d < 3; ++d) {
    u.lo[d] = a.lo[d] < b.lo[d] ? a.lo[d] : b.lo[d];
    u.hi[d] = a.hi[d] > b.hi[d] ? a.hi[d] : b.hi[d];
  }
  return u;
}

// The cells both hold (empty, with lo == hi, where they do not meet).
inline Box intersection(const Box& a, const Box& b) {
  Box c;
  for (int d = 0; d < 3; ++d) {
    c.lo[d] = a.lo[d] > b.lo[d] ? a.lo[d] : b.lo[d];
    const int hi = a.hi[d] < b.hi[d] ? a.hi[d] : b.hi[d];
    c.hi[d] = hi > c.lo[d] ? hi : c.lo[d];
  }
  return c;
}

// The cells of a outside b as at most 6 disjoint boxes (slabs below and above b along x, then
// along y within b's x-range, then along z within its x-y range); returns how many were written.
inline int difference(const Box& a, const Box& b, Box out[6]) {
  const Box cut = intersection(a, b);
  if (cut.empty()) {
    out[0] = a;
    return a.empty() ? 0 : 1;
  }
  int n = 0;
  Box rest = a;
  for (int d = 0; d < 3; ++d) {
    Box below = rest, above = rest;
    below.hi[d] = cut.lo[d];
    above.lo[d] = cut.hi[d];
    if (!below.empty()) out[n++] = below;
    if (!above.empty()) out[n++] = above;
    rest.lo[d] = cut.lo[d];
    rest.hi[d] = cut.hi[d];
  }
  return n;
}

}  // namespace eulerfsi
