#pragma once
// Face-to-centre averages for output and diagnostics: uc(i) = (u(i-1) + u(i)) / 2 along the
// component's own direction.
#include "core/launch.hpp"
#include "core/types.hpp"

namespace eulerfsi::kernels {

inline void face_to_centre(const Field3& out, const Field3& face, int dir, const Box& box) {
  const int di = dir == 0, dj = dir == 1, dk = dir == 2;
  for_each_cell("eulerfsi::interp::face_to_centre", box, KOKKOS_LAMBDA(int i, int j, int k) {
    out(i, j, k) = 0.5 * (face(i, j, k) + face(i - di, j - dj, k - dk));
  });
}

}  // namespace eulerfsi::kernels
