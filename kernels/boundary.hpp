#pragma once
// Ghost layers in the y and z directions (x is periodic and filled by the halo exchange):
//   Periodic:  f(-1-m) = f(n-1-m),             f(n+m) = f(m)
//   Even:      f(-1-m) = f(m)                   (cell-centred scalar, zero normal gradient)
//   Tangent:   f(-1-m) = 2 f_wall_lo - f(m)     (velocity parallel to the wall: no-slip at the wall)
//   Normal:    f(-1) = 0, f(-1-m) = -f(-1+m)    (velocity through the wall, stored on the wall face)
//   WallFace:  f(n-1) = 0 only                  (Normal's owned high face: what div_h u reads once the
//                                                 owned cells changed; the ghosts keep the last fill)
#include "core/types.hpp"

namespace eulerfsi::kernels {

enum class GhostRule { Periodic, Even, Tangent, Normal, WallFace };

// The ghost layers of one line of f along DIR (the other two indices fixed), storage index s.
// A field on a window (src/solid/solid_window.hpp) numbers its cells from `origin` along DIR and
// may hold the ghosts of one side only (low, high).
template <int DIR>
struct GhostLine {
  Field3 f;
  int n;  // owned cells along DIR
  GhostRule rule;
  double wall_lo, wall_hi;
  int origin = 0;
  bool low = true, high = true;

  KOKKOS_FORCEINLINE_FUNCTION double& at(int a, int b, int s) const {
    return DIR == 1 ? f(a, s, b) : f(a, b, s);
  }
  KOKKOS_INLINE_FUNCTION void operator()(int a, int b) const {
    constexpr int G = kGhost;
    const int lo = G - origin, hi = G + n - 1 - origin;  // first and last owned index
    switch (rule) {
      case GhostRule::Periodic:
        for (int m = 0; m < G; ++m) {
          if (low) at(a, b, lo - 1 - m) = at(a, b, hi - m);
          if (high) at(a, b, hi + 1 + m) = at(a, b, lo + m);
        }
        break;
      case GhostRule::Even:
        for (int m = 0; m < G; ++m) {
          if (low) at(a, b, lo - 1 - m) = at(a, b, lo + m);
          if (high) at(a, b, hi + 1 + m) = at(a, b, hi - m);
        }
        break;
      case GhostRule::Tangent:
        for (int m = 0; m < G; ++m) {
          if (low) at(a, b, lo - 1 - m) = 2.0 * wall_lo - at(a, b, lo + m);
          if (high) at(a, b, hi + 1 + m) = 2.0 * wall_hi - at(a, b, hi - m);
        }
        break;
      case GhostRule::Normal:
        // the low wall face is index G-1, the high wall face index G+n-1 (the last owned face)
        if (low) {
          at(a, b, lo - 1) = 0.0;
          for (int m = 1; m < G; ++m) at(a, b, lo - 1 - m) = -at(a, b, lo - 1 + m);
        }
        if (high) {
          at(a, b, hi) = 0.0;
          for (int m = 1; m <= G; ++m) at(a, b, hi + m) = -at(a, b, hi - m);
        }
        break;
      case GhostRule::WallFace:
        if (high) at(a, b, hi) = 0.0;
        break;
    }
  }
};

// n: owned cells along `dir` (1 or 2); the ghost layers along `dir` are filled over the x-planes
// [x_lo, x_hi) (default: all, ghosts included) and every other index, so edges and corners follow.
inline void fill_ghosts(const Field3& f, int dir, int n, GhostRule rule, double wall_lo, double wall_hi, int x_lo = 0,
                        int x_hi = -1) {
  const int e0 = x_hi < 0 ? static_cast<int>(f.extent(0)) : x_hi;
  const int eb = static_cast<int>(f.extent(dir == 1 ? 2 : 1));
  const Policy2 plane({x_lo, 0}, {e0 > x_lo ? e0 : x_lo, eb});
  if (dir == 1) {
    Kokkos::parallel_for("eulerfsi::boundary::ghosts_y", plane, GhostLine<1>{f, n, rule, wall_lo, wall_hi});
  } else {
    Kokkos::parallel_for("eulerfsi::boundary::ghosts_z", plane, GhostLine<2>{f, n, rule, wall_lo, wall_hi});
  }
}

// The same on a field stored on a window: its numbering along `dir` starts at storage index
// `origin`, and only the sides it holds (low, high) are filled; x-planes [x_lo, x_hi) of its own.
inline void fill_window_ghosts(const Field3& f, int dir, int n, GhostRule rule, int origin, bool low, bool high,
                               int x_lo, int x_hi) {
  const int eb = static_cast<int>(f.extent(dir == 1 ? 2 : 1));
  const Policy2 plane({x_lo, 0}, {x_hi > x_lo ? x_hi : x_lo, eb});
  if (dir == 1) {
    Kokkos::parallel_for("eulerfsi::boundary::ghosts_y", plane, GhostLine<1>{f, n, rule, 0.0, 0.0, origin, low, high});
  } else {
    Kokkos::parallel_for("eulerfsi::boundary::ghosts_z", plane, GhostLine<2>{f, n, rule, 0.0, 0.0, origin, low, high});
  }
}

}  // namespace eulerfsi::kernels
