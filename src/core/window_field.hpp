#pragma once
// A scalar field stored on a window of the local slab: data(i - lo[0], j - lo[1], k - lo[2]) holds
// cell (i, j, k) in storage indices, for the cells of window() only. A body's fields live on a
// window that follows it (src/solid/solid_window.hpp), so its memory follows its size; a Field3
// converts to the window of the whole slab. Kernels index it exactly like a Field3.
#include "core/types.hpp"

namespace eulerfsi {

struct WindowField {
  Field3 data;
  int lo[3] = {0, 0, 0};

  WindowField() = default;
  // The whole slab (implicit: a Field3 is the window of everything).
  WindowField(const Field3& whole) : data(whole) {}  // NOLINT(google-explicit-constructor)
  WindowField(const Field3& storage, const int origin[3]) : data(storage) {
    for (int d = 0; d < 3; ++d) lo[d] = origin[d];
  }

  KOKKOS_FORCEINLINE_FUNCTION double& operator()(int i, int j, int k) const {
    return data(i - lo[0], j - lo[1], k - lo[2]);
  }
  // The cells it holds, in storage indices.
  Box window() const {
    Box b;
    for (int d = 0; d < 3; ++d) {
      b.lo[d] = lo[d];
      b.hi[d] = lo[d] + int(data.extent(d));
    }
    return b;
  }
  bool allocated() const { return data.extent(0) > 0; }
};

}  // namespace eulerfsi
