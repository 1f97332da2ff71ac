#pragma once
// Storage of one soft body: the solid volume fraction psi and the left Cauchy-Green tensor B
// (the paper's xi), six independent components, all at cell centres.
#include "core/types.hpp"
#include "core/window_field.hpp"

namespace eulerfsi::kernels {

// Component order of the symmetric tensor B.
enum TensorComponent : int { XX = 0, YY = 1, ZZ = 2, XY = 3, XZ = 4, YZ = 5 };
constexpr int kTensorComponents = 6;

// (row, column) -> storage component, for writing sums over indices.
KOKKOS_INLINE_FUNCTION int tensor_index(int a, int b) {
  if (a == b) return a;
  const int lo = a < b ? a : b, hi = a < b ? b : a;
  return lo == 0 ? (hi == 1 ? XY : XZ) : YZ;
}

// Cell-centre coordinates from storage indices: x_d(s) = x0[d] + s h[d], x0[d] = grid.centre(d, 0).
struct CellCentres {
  double x0[3];
  double h[3];
  KOKKOS_INLINE_FUNCTION double operator()(int d, int s) const { return x0[d] + s * h[d]; }
};

struct Tensor6 {
  WindowField c[kTensorComponents];
};

// Three cell-centred fields a kernel may overwrite: buffers of a solid model that hold nothing
// between its substeps (SolidModel::scratch).
struct Scratch3 {
  WindowField c[3];
};

}  // namespace eulerfsi::kernels
