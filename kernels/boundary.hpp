#pragma once
// Ghost layers in the y and z directions (x is periodic and filled by the halo exchange):
//   Periodic:  f(-1-m) = f(n-1-m),             f(n+m) = f(m)
//   Even:      f(-1-m) = f(m)                   (cell-centred scalar, zero normal gradient)
//   Tangent:   f(-1-m) = 2 f_wall_lo - f(m)     (velocity parallel to the wall: no-slip at the wall)
//   Normal:    f(-1) = 0, f(-1-m) = -f(-1+m)    (velocity through the wall, stored on the wall face)
#include "core/types.hpp"

namespace eulerfsi::kernels {

enum class GhostRule { Periodic, Even, Tangent, Normal };

// f at the index `idx` with its `dir` component replaced by s.
KOKKOS_FORCEINLINE_FUNCTION double& along(const Field3& f, const int idx[3], int dir, int s) {
  return dir == 0 ? f(s, idx[1], idx[2]) : (dir == 1 ? f(idx[0], s, idx[2]) : f(idx[0], idx[1], s));
}

// n: owned cells along `dir`; the ghost slabs along `dir` are filled over every other index.
inline void fill_ghosts(const Field3& f, int dir, int n, GhostRule rule, double wall_lo, double wall_hi) {
  const int G = kGhost;
  const int e0 = static_cast<int>(f.extent(0)), e1 = static_cast<int>(f.extent(1)), e2 = static_cast<int>(f.extent(2));
  // iterate m over [0, G] on the chosen axis: G+1 layers covers the extra wall-face layer of Normal
  int hi[3] = {e0, e1, e2};
  hi[dir] = G + 1;
  Policy3 policy({0, 0, 0}, {hi[0], hi[1], hi[2]});
  Kokkos::parallel_for("eulerfsi::boundary::fill_ghosts", policy, KOKKOS_LAMBDA(int a, int b, int c) {
    int idx[3] = {a, b, c};
    const int m = idx[dir];
    const int lo_first = G;          // first owned index
    const int hi_last = G + n - 1;   // last owned index
    switch (rule) {
      case GhostRule::Periodic:
        if (m < G) {
          along(f, idx, dir, lo_first - 1 - m) = along(f, idx, dir, hi_last - m);
          along(f, idx, dir, hi_last + 1 + m) = along(f, idx, dir, lo_first + m);
        }
        break;
      case GhostRule::Even:
        if (m < G) {
          along(f, idx, dir, lo_first - 1 - m) = along(f, idx, dir, lo_first + m);
          along(f, idx, dir, hi_last + 1 + m) = along(f, idx, dir, hi_last - m);
        }
        break;
      case GhostRule::Tangent:
        if (m < G) {
          along(f, idx, dir, lo_first - 1 - m) = 2.0 * wall_lo - along(f, idx, dir, lo_first + m);
          along(f, idx, dir, hi_last + 1 + m) = 2.0 * wall_hi - along(f, idx, dir, hi_last - m);
        }
        break;
      case GhostRule::Normal:
        // low wall face is index G-1, high wall face is index G+n-1 (the last owned face)
        if (m == 0) {
          along(f, idx, dir, lo_first - 1) = 0.0;
          along(f, idx, dir, hi_last) = 0.0;
        } else {
          if (m < G) along(f, idx, dir, lo_first - 1 - m) = -along(f, idx, dir, lo_first - 1 + m);
          along(f, idx, dir, hi_last + m) = -along(f, idx, dir, hi_last - m);
        }
        break;
    }
  });
}

}  // namespace eulerfsi::kernels
