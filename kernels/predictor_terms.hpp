#pragma once
// The pointwise part of the RK3 predictor with implicit volume penalization (Kadoch et al. 2012):
//   u* = [u^k + dt (gamma rhs^k + zeta rhs^(k-1)) + pen u_wall] / (1 + pen),   pen = alpha dt chi / eta
// for the momentum kernels that compute rhs^k and u* in one pass (kernels/momentum_predictor.hpp).
#include "core/types.hpp"

namespace eulerfsi::kernels {

struct PredictorTerms {
  double* rhs_old_to_star[3];  // rhs^(k-1) on entry, u* on exit (the same cell: no extra field)
  // the x-independent wall mask chi(j, k) per component, row-major with row stride chi_stride; a
  // component without one points at a row of zeros with stride 0 (no branch in the loops)
  const double* chi[3];
  long chi_stride[3];
  double a = 0.0, b = 0.0;  // dt gamma, dt zeta
  double penal = 0.0;       // alpha dt / eta
  double u_wall[3] = {0.0, 0.0, 0.0};

  // chi of the storage row j (indexed with the storage k)
  KOKKOS_FORCEINLINE_FUNCTION const double* chi_row(int d, int j) const { return chi[d] + j * chi_stride[d]; }
  template <int D>
  KOKKOS_FORCEINLINE_FUNCTION double star(double u, double rhs, double rhs_old, double chi_value) const {
    const double pen = penal * chi_value;
    return (u + a * rhs + b * rhs_old + pen * u_wall[D]) / (1.0 + pen);
  }
};

}  // namespace eulerfsi::kernels
