#pragma once
// Explicit right-hand side of the momentum equation at the staggered velocity points:
//   rhs_D = -d/dx_E (u_E u_D) + d/dx_E [ mu (du_D/dx_E + du_E/dx_D) ]
// second-order central differences in conservative form on the MAC grid. mu is the mixture
// viscosity at cell centres; edge values average the four neighbouring cells.
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/momentum_fluxes.hpp"
#include "kernels/momentum_sweep.hpp"
#include "kernels/offsets.hpp"

namespace eulerfsi::kernels {

template <int D, bool Uniform>
struct MomentumRhs {
  static constexpr int E1 = (D + 1) % 3;
  static constexpr int E2 = (D + 2) % 3;
  Field3 rhs;
  Field3 u0, u1, u2;  // u, v, w
  Field3 mu;
  double mu_uniform;
  double inv_h[3];

  // rhs_D at the flat index c (every field shares one layout: strides sD, s1, s2).
  KOKKOS_FORCEINLINE_FUNCTION static double value(const double* KOKKOS_RESTRICT uD, const double* KOKKOS_RESTRICT uE1,
                                                  const double* KOKKOS_RESTRICT uE2, const double* KOKKOS_RESTRICT m,
                                                  double mu0, long c, long sD, long s1, long s2, double ihD,
                                                  double ih1, double ih2) {
    const double fn =
        (normal_flux_at<Uniform>(uD, m, mu0, c + sD, sD, ihD) - normal_flux_at<Uniform>(uD, m, mu0, c, sD, ihD)) * ihD;
    const double f1 = (shear_flux_at<D, E1, Uniform>(uD, uE1, m, mu0, c, sD, s1, ihD, ih1) -
                       shear_flux_at<D, E1, Uniform>(uD, uE1, m, mu0, c - s1, sD, s1, ihD, ih1)) *
                      ih1;
    const double f2 = (shear_flux_at<D, E2, Uniform>(uD, uE2, m, mu0, c, sD, s2, ihD, ih2) -
                       shear_flux_at<D, E2, Uniform>(uD, uE2, m, mu0, c - s2, sD, s2, ihD, ih2)) *
                      ih2;
    return -(fn + f1 + f2);
  }

  KOKKOS_INLINE_FUNCTION const double* field(int a) const { return (a == 0 ? u0 : (a == 1 ? u1 : u2)).data(); }

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    const long st[3] = {long(rhs.stride(0)), long(rhs.stride(1)), 1};
    const long c = i * st[0] + j * st[1] + k;
    rhs.data()[c] = value(field(D), field(E1), field(E2), Uniform ? nullptr : mu.data(), mu_uniform, c, st[D], st[E1],
                          st[E2], inv_h[D], inv_h[E1], inv_h[E2]);
  }
};

// All three components in one pass, one cell per call: the GPU form (hosts run
// kernels/momentum_sweep.hpp, which keeps each flux for the next cell instead of computing it again).
template <bool Uniform>
struct MomentumRhsAll {
  MomentumRhs<0, Uniform> fx;
  MomentumRhs<1, Uniform> fy;
  MomentumRhs<2, Uniform> fz;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    fx(i, j, k);
    fy(i, j, k);
    fz(i, j, k);
  }
};

template <bool Uniform>
inline void momentum_rhs_impl(const Velocity& rhs, const Velocity& u, const Field3& mu, double mu_uniform,
                              const double h[3], const Box& box, const char* label) {
  const double inv_h[3] = {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]};
  if constexpr (kHostKernels) {
    const long st[3] = {long(rhs.c[0].stride(0)), long(rhs.c[0].stride(1)), 1};
    const MomentumSweep<Uniform> f{{rhs.c[0].data(), rhs.c[1].data(), rhs.c[2].data()},
                                   {u.c[0].data(), u.c[1].data(), u.c[2].data()},
                                   Uniform ? nullptr : mu.data(),
                                   mu_uniform,
                                   {inv_h[0], inv_h[1], inv_h[2]},
                                   {st[0], st[1], st[2]}};
    momentum_sweep(f, box, label);
  } else {
    const MomentumRhsAll<Uniform> f{{rhs.c[0], u.c[0], u.c[1], u.c[2], mu, mu_uniform, {inv_h[0], inv_h[1], inv_h[2]}},
                                    {rhs.c[1], u.c[0], u.c[1], u.c[2], mu, mu_uniform, {inv_h[0], inv_h[1], inv_h[2]}},
                                    {rhs.c[2], u.c[0], u.c[1], u.c[2], mu, mu_uniform, {inv_h[0], inv_h[1], inv_h[2]}}};
    for_each_cell(label, box, f);
  }
}

// Fills rhs[D] over `box` for all three components with the constant viscosity mu.
inline void momentum_rhs(const Velocity& rhs, const Velocity& u, double mu, const double h[3], const Box& box) {
  momentum_rhs_impl<true>(rhs, u, Field3(), mu, h, box, "eulerfsi::momentum::rhs");
}

// The same with the viscosity field mu (cell centres, ghosts filled), edges averaged.
inline void momentum_rhs(const Velocity& rhs, const Velocity& u, const Field3& mu, const double h[3], const Box& box) {
  momentum_rhs_impl<false>(rhs, u, mu, 0.0, h, box, "eulerfsi::momentum::rhs_mixture");
}

}  // namespace eulerfsi::kernels
