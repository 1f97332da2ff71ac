#pragma once
// One way to run a per-cell body over a Box on every backend:
//  - GPUs: a 3-D MDRange, one thread per cell, k fastest (coalesced);
//  - host backends: a 2-D MDRange over (i, j) with a plain inner loop over k, so the body is
//    inlined into a contiguous loop the compiler can vectorise (Kokkos 3.4's 3-D host tiles call
//    the body once per cell, which costs several times the arithmetic of our stencils).
#include "core/types.hpp"

namespace eulerfsi {

// Bodies given to for_each_cell write only their own cell, so iterations along k are independent:
// tell the compiler so it vectorises despite the possible aliasing of Views.
#if defined(__clang__)
#define EULERFSI_INDEPENDENT_LOOP _Pragma("clang loop vectorize(assume_safety)")
#elif defined(__GNUC__)
#define EULERFSI_INDEPENDENT_LOOP _Pragma("GCC ivdep")
#else
#define EULERFSI_INDEPENDENT_LOOP
#endif

constexpr bool kHostKernels = Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible;

// The box's upper bound in direction d, never below its lower one (an empty box: no iterations).
inline int plane_hi(const Box& b, int d) { return b.hi[d] > b.lo[d] ? b.hi[d] : b.lo[d]; }

inline Policy2 plane_policy(const Box& b) { return Policy2({b.lo[0], b.lo[1]}, {plane_hi(b, 0), plane_hi(b, 1)}); }

// for_each_cell / for_each_row on hosts: one i-plane per tile, handed out dynamically. A body's
// boxes are small and their work is uneven (the cells near its surface), and Kokkos' default host
// tile of two planes split an odd number of planes 10 : 7 between two threads; the map's kernels
// then scaled 1.6-1.8x on two threads. Each cell writes only itself, so the order is free;
// reductions keep plane_policy's static split, so that their summation order stays fixed.
using DynamicPolicy2 = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2, Kokkos::Iterate::Right, Kokkos::Iterate::Right>,
                                             Kokkos::Schedule<Kokkos::Dynamic>>;
inline DynamicPolicy2 row_policy(const Box& b) {
  const int rows = plane_hi(b, 1) - b.lo[1];
  return DynamicPolicy2({b.lo[0], b.lo[1]}, {plane_hi(b, 0), plane_hi(b, 1)}, {1, rows > 0 ? rows : 1});
}

// f(i, j, k) for every cell of the box; f writes nothing that another cell's f reads.
template <class F>
void for_each_cell(const char* label, const Box& b, const F& f) {
  if constexpr (kHostKernels) {
    const int k0 = b.lo[2], k1 = b.hi[2];
    Kokkos::parallel_for(label, row_policy(b), KOKKOS_LAMBDA(int i, int j) {
      EULERFSI_INDEPENDENT_LOOP
      for (int k = k0; k < k1; ++k) f(i, j, k);
    });
  } else {
    Kokkos::parallel_for(label, b.policy(), f);
  }
}

// The same for a body with a row method, f.row(i, j, k0, k1), that runs the k loop itself (set up
// once per row, so it vectorises); GPUs call f(i, j, k) per cell.
template <class F>
void for_each_row(const char* label, const Box& b, const F& f) {
  if constexpr (kHostKernels) {
    const int k0 = b.lo[2], k1 = b.hi[2];
    Kokkos::parallel_for(label, row_policy(b), KOKKOS_LAMBDA(int i, int j) { f.row(i, j, k0, k1); });
  } else {
    Kokkos::parallel_for(label, b.policy(), f);
  }
}

// f.plane(i, j0, j1, k0, k1) for every i-plane of the box on hosts, dynamically scheduled: one
// thread walks a whole plane, row after row, so a body can carry values from one row to the next;
// GPUs call f(i, j, k) per cell.
template <class F>
void for_each_plane(const char* label, const Box& b, const F& f) {
  if constexpr (kHostKernels) {
    const int j0 = b.lo[1], j1 = b.hi[1], k0 = b.lo[2], k1 = b.hi[2];
    Kokkos::RangePolicy<ExecSpace, Kokkos::Schedule<Kokkos::Dynamic>> planes(b.lo[0], plane_hi(b, 0));
    Kokkos::parallel_for(label, planes.set_chunk_size(1), KOKKOS_LAMBDA(int i) { f.plane(i, j0, j1, k0, k1); });
  } else {
    Kokkos::parallel_for(label, b.policy(), f);
  }
}

// f(i, j, k, acc) for every cell, combined by a built-in reducer (Sum, Max, Min).
template <class F, class Reducer>
void reduce_cells(const char* label, const Box& b, const F& f, const Reducer& reducer) {
  using value_type = typename Reducer::value_type;
  if constexpr (kHostKernels) {
    const int k0 = b.lo[2], k1 = b.hi[2];
    Kokkos::parallel_reduce(label, plane_policy(b), KOKKOS_LAMBDA(int i, int j, value_type& acc) {
      for (int k = k0; k < k1; ++k) f(i, j, k, acc);
    }, reducer);
  } else {
    Kokkos::parallel_reduce(label, b.policy(), f, reducer);
  }
}

// The same for a body with a row method, reducer.join(acc, f.row_reduce(i, j, k0, k1)) on host
// backends (the row's k loop runs in the body, so it vectorises); GPUs call f(i, j, k, acc).
template <class F, class Reducer>
void reduce_rows(const char* label, const Box& b, const F& f, const Reducer& reducer) {
  using value_type = typename Reducer::value_type;
  if constexpr (kHostKernels) {
    const int k0 = b.lo[2], k1 = b.hi[2];
    Kokkos::parallel_reduce(label, plane_policy(b), KOKKOS_LAMBDA(int i, int j, value_type& acc) {
      reducer.join(acc, f.row_reduce(i, j, k0, k1));
    }, reducer);
  } else {
    Kokkos::parallel_reduce(label, b.policy(), f, reducer);
  }
}

}  // namespace eulerfsi
