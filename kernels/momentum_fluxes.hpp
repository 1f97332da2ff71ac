#pragma once
// The momentum fluxes on the MAC grid, shared by the per-cell kernel (kernels/momentum.hpp) and
// the host sweep that computes each once (kernels/momentum_sweep.hpp).
#include "core/types.hpp"

namespace eulerfsi::kernels {

struct Velocity {
  Field3 c[3];
};

// Flux of D-momentum through the cell centred at c in direction D:
//   F = uc_D^2 - 2 mu du_D/dx_D, with uc_D the centre average of the two faces of the cell.
// Flux of D-momentum in direction E through the edge at (c + e_D/2 + e_E/2):
//   F = (u_D u_E)_edge - mu_edge (du_D/dx_E + du_E/dx_D)
// Uniform: the viscosity is the constant mu_uniform wherever the kernel runs (the field mu is
// not read: one stream less, and no edge averages).
// rhs_D = -(F_DD(i+e_D) - F_DD(i))/h_D - sum_{E != D} (F_DE(i) - F_DE(i - e_E))/h_E, written on
// raw pointers with unit offsets s_A (all fields share one layout): the compiler then sees that
// rhs does not alias the inputs and vectorises the k loop on CPUs.
template <int D, int E, bool Uniform>
KOKKOS_FORCEINLINE_FUNCTION double shear_flux_at(const double* KOKKOS_RESTRICT uD, const double* KOKKOS_RESTRICT uE,
                                                  const double* KOKKOS_RESTRICT mu, double mu_uniform, long c, long sD,
                                                  long sE, double ihD, double ihE) {
  const double mu_edge = Uniform ? mu_uniform : 0.25 * (mu[c] + mu[c + sD] + mu[c + sE] + mu[c + sD + sE]);
  return 0.25 * (uD[c] + uD[c + sE]) * (uE[c] + uE[c + sD]) -
         mu_edge * ((uD[c + sE] - uD[c]) * ihE + (uE[c + sD] - uE[c]) * ihD);
}

template <bool Uniform>
KOKKOS_FORCEINLINE_FUNCTION double normal_flux_at(const double* KOKKOS_RESTRICT uD, const double* KOKKOS_RESTRICT mu,
                                                   double mu_uniform, long c, long sD, double ihD) {
  const double uc = 0.5 * (uD[c] + uD[c - sD]);
  return uc * uc - 2.0 * (Uniform ? mu_uniform : mu[c]) * (uD[c] - uD[c - sD]) * ihD;
}

}  // namespace eulerfsi::kernels
