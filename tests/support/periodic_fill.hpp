#pragma once
// Test helper: fill the kGhost ghost layers of an n[0] x n[1] x n[2] periodic field by copying,
// x first, then y, then z, so edges and corners are filled too.
#include "core/types.hpp"

namespace eulerfsi::test_support {

inline void fill_periodic(const Field3& f, const int n[3]) {
  const int e0 = n[0] + 2 * kGhost, e1 = n[1] + 2 * kGhost, e2 = n[2] + 2 * kGhost;
  for (int d = 0; d < 3; ++d) {
    const int nd = n[d];
    Kokkos::parallel_for("eulerfsi::test::fill_periodic", Policy3({0, 0, 0}, {e0, e1, e2}),
                         KOKKOS_LAMBDA(int i, int j, int k) {
      int s[3] = {i, j, k};
      const int x = s[d];
      if (x >= kGhost && x < kGhost + nd) return;
      s[d] = x < kGhost ? x + nd : x - nd;
      f(i, j, k) = f(s[0], s[1], s[2]);
    });
  }
}

}  // namespace eulerfsi::test_support
