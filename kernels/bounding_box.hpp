#pragma once
// The bounding box of the cells where a field is non-zero, in one pass: a custom reducer that
// carries the six extents together (six Max reductions, one per extent, read the box six times).
#include "core/launch.hpp"
#include "core/types.hpp"
#include "core/window_field.hpp"

namespace eulerfsi::kernels {

// Extents of the cells seen so far: lo = smallest index, hi = largest (inclusive); lo > hi: none.
struct CellExtent {
  int lo[3], hi[3];
};

// Kokkos custom reducer (min of lo, max of hi). Kokkos 3.4 joins through volatile references and
// 4.x rejects them, so both overloads are given (docs: STYLE, "custom reducers").
struct CellExtentReducer {
  using reducer = CellExtentReducer;
  using value_type = CellExtent;
  using result_view_type = Kokkos::View<value_type, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;

  value_type* value;
  explicit CellExtentReducer(value_type& v) : value(&v) {}

  // dst takes in src (D, S: the extent, volatile or not)
  template <class D, class S>
  KOKKOS_INLINE_FUNCTION static void merge(D& dst, const S& src) {
    for (int d = 0; d < 3; ++d) {
      if (src.lo[d] < dst.lo[d]) dst.lo[d] = src.lo[d];
      if (src.hi[d] > dst.hi[d]) dst.hi[d] = src.hi[d];
    }
  }
  KOKKOS_INLINE_FUNCTION void join(value_type& dst, const value_type& src) const { merge(dst, src); }
  KOKKOS_INLINE_FUNCTION void join(volatile value_type& dst, const volatile value_type& src) const { merge(dst, src); }
  KOKKOS_INLINE_FUNCTION void init(value_type& v) const {
    for (int d = 0; d < 3; ++d) {
      v.lo[d] = 1 << 30;
      v.hi[d] = -(1 << 30);
    }
  }
  KOKKOS_INLINE_FUNCTION value_type& reference() const { return *value; }
  result_view_type view() const { return result_view_type(value); }
  KOKKOS_INLINE_FUNCTION bool references_scalar() const { return true; }
};

// The cells where a field is non-zero: per cell (GPUs) or per row (hosts: the row's first and last
// such cell, found by scanning from either end, instead of six comparisons per cell).
struct NonZeroExtent {
  WindowField known;

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, CellExtent& acc) const {
    if (known(i, j, k) == 0.0) return;
    const int c[3] = {i, j, k};
    for (int d = 0; d < 3; ++d) {
      if (c[d] < acc.lo[d]) acc.lo[d] = c[d];
      if (c[d] > acc.hi[d]) acc.hi[d] = c[d];
    }
  }
  CellExtent row_reduce(int i, int j, int k0, int k1) const {
    CellExtent e;
    CellExtentReducer(e).init(e);
    const double* row = &known(i, j, k0);
    int first = 0;
    while (first < k1 - k0 && row[first] == 0.0) ++first;
    if (first == k1 - k0) return e;
    int last = k1 - k0 - 1;
    while (row[last] == 0.0) --last;
    e.lo[0] = e.hi[0] = i;
    e.lo[1] = e.hi[1] = j;
    e.lo[2] = k0 + first;
    e.hi[2] = k0 + last;
    return e;
  }
};

// out = the bounding box (half-open) of the cells of `box` where `known` is non-zero; false (out
// untouched) when there is none.
inline bool known_bounding_box(const WindowField& known, const Box& box, Box& out) {
  CellExtent e;
  reduce_rows("eulerfsi::solid::known_extent", box, NonZeroExtent{known}, CellExtentReducer(e));
  if (e.hi[0] < e.lo[0]) return false;
  for (int d = 0; d < 3; ++d) {
    out.lo[d] = e.lo[d];
    out.hi[d] = e.hi[d] + 1;
  }
  return true;
}

}  // namespace eulerfsi::kernels
