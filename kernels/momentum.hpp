#pragma once
// Explicit right-hand side of the momentum equation at the staggered velocity points:
//   rhs_D = -d/dx_E (u_E u_D) + d/dx_E [ mu (du_D/dx_E + du_E/dx_D) ]
// second-order central differences in conservative form on the MAC grid. mu is the mixture
// viscosity at cell centres; edge values average the four neighbouring cells.
#include "core/types.hpp"
#include "kernels/offsets.hpp"

namespace eulerfsi::kernels {

struct Velocity {
  Field3 c[3];
};

// Flux of D-momentum through the cell centred at (i,j,k) in direction D:
//   F = uc_D^2 - 2 mu du_D/dx_D, with uc_D the centre average of the two faces of the cell.
template <int D>
KOKKOS_FORCEINLINE_FUNCTION double normal_flux(const Field3& uD, const Field3& mu, double inv_h, int i, int j, int k) {
  const double up = uD(i, j, k);
  const double um = shifted<D>(uD, i, j, k, -1);
  const double uc = 0.5 * (up + um);
  return uc * uc - 2.0 * mu(i, j, k) * (up - um) * inv_h;
}

// Flux of D-momentum in direction E through the edge at (i + e_D/2 + e_E/2):
//   F = (u_D u_E)_edge - mu_edge (du_D/dx_E + du_E/dx_D)
// Uniform: mu(i,j,k) holds one value everywhere (single phase), so the edge average is skipped.
template <int D, int E, bool Uniform>
KOKKOS_FORCEINLINE_FUNCTION double shear_flux(const Field3& uD, const Field3& uE, const Field3& mu, double inv_hD,
                                               double inv_hE, int i, int j, int k) {
  const double uD0 = uD(i, j, k);
  const double uD1 = shifted<E>(uD, i, j, k, 1);
  const double uE0 = uE(i, j, k);
  const double uE1 = shifted<D>(uE, i, j, k, 1);
  const double mu_edge = Uniform ? mu(i, j, k)
                                 : 0.25 * (mu(i, j, k) + shifted<D>(mu, i, j, k, 1) + shifted<E>(mu, i, j, k, 1) +
                                           shifted<D, E>(mu, i, j, k, 1, 1));
  return 0.25 * (uD0 + uD1) * (uE0 + uE1) - mu_edge * ((uD1 - uD0) * inv_hE + (uE1 - uE0) * inv_hD);
}

// rhs_D = -(F_DD(i+e_D) - F_DD(i))/h_D - sum_{E != D} (F_DE(i) - F_DE(i - e_E))/h_E
template <int D, bool Uniform>
struct MomentumRhs {
  static constexpr int E1 = (D + 1) % 3;
  static constexpr int E2 = (D + 2) % 3;
  Field3 rhs;
  Field3 u0, u1, u2;  // u, v, w
  Field3 mu;
  double inv_h[3];

  KOKKOS_FORCEINLINE_FUNCTION const Field3& comp(int c) const { return c == 0 ? u0 : (c == 1 ? u1 : u2); }

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    const Field3& uD = comp(D);
    const Field3& uE1 = comp(E1);
    const Field3& uE2 = comp(E2);
    const double fn = (normal_flux<D>(uD, mu, inv_h[D], i + Unit<D>::i, j + Unit<D>::j, k + Unit<D>::k) -
                       normal_flux<D>(uD, mu, inv_h[D], i, j, k)) *
                      inv_h[D];
    const double f1 = (shear_flux<D, E1, Uniform>(uD, uE1, mu, inv_h[D], inv_h[E1], i, j, k) -
                       shear_flux<D, E1, Uniform>(uD, uE1, mu, inv_h[D], inv_h[E1], i - Unit<E1>::i, j - Unit<E1>::j,
                                         k - Unit<E1>::k)) *
                      inv_h[E1];
    const double f2 = (shear_flux<D, E2, Uniform>(uD, uE2, mu, inv_h[D], inv_h[E2], i, j, k) -
                       shear_flux<D, E2, Uniform>(uD, uE2, mu, inv_h[D], inv_h[E2], i - Unit<E2>::i, j - Unit<E2>::j,
                                         k - Unit<E2>::k)) *
                      inv_h[E2];
    rhs(i, j, k) = -(fn + f1 + f2);
  }
};

template <bool Uniform>
inline void momentum_rhs_impl(const Velocity& rhs, const Velocity& u, const Field3& mu, const double h[3], const Box& box) {
  const double inv_h[3] = {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]};
  MomentumRhs<0, Uniform> fx{rhs.c[0], u.c[0], u.c[1], u.c[2], mu, {inv_h[0], inv_h[1], inv_h[2]}};
  MomentumRhs<1, Uniform> fy{rhs.c[1], u.c[0], u.c[1], u.c[2], mu, {inv_h[0], inv_h[1], inv_h[2]}};
  MomentumRhs<2, Uniform> fz{rhs.c[2], u.c[0], u.c[1], u.c[2], mu, {inv_h[0], inv_h[1], inv_h[2]}};
  Kokkos::parallel_for("eulerfsi::momentum::rhs_u", box.policy(), fx);
  Kokkos::parallel_for("eulerfsi::momentum::rhs_v", box.policy(), fy);
  Kokkos::parallel_for("eulerfsi::momentum::rhs_w", box.policy(), fz);
}

// Fills rhs[D] over `box` for all three components. uniform_viscosity: mu is the same everywhere
// (no solid), which saves the edge averages.
inline void momentum_rhs(const Velocity& rhs, const Velocity& u, const Field3& mu, const double h[3], const Box& box,
                         bool uniform_viscosity = false) {
  if (uniform_viscosity) {
    momentum_rhs_impl<true>(rhs, u, mu, h, box);
  } else {
    momentum_rhs_impl<false>(rhs, u, mu, h, box);
  }
}

}  // namespace eulerfsi::kernels
