#pragma once
// Conservative interface sharpening, Olsson, Kreiss & Zahedi 2007 (J. Comput. Phys. 225, 785):
// one pseudo-time step of
//   dpsi/dtau + div[ psi (1 - psi) n ] = div[ eps (grad psi . n) n ],   n = grad psi / |grad psi|
// with n frozen during the step (computed once per call from psi). It counteracts the numerical
// diffusion of the WENO advection, which otherwise widens the edge of a particle without bound and
// leaves a halo of small psi in which B has no meaning. The equilibrium profile across the
// interface is psi = 1 / (1 + exp(-d / eps)). Unlike the isotropic form of Olsson & Kreiss 2005
// (diffusion eps lap psi, kept below as `sharpening_rhs_isotropic` for comparison), compression
// and diffusion both act along n only, so they balance on a curved interface too: no tangential
// diffusion moves the level sets (the isotropic form shrinks a sphere and flattens a deformed
// particle). The flux form keeps the volume to round-off; walls (even ghosts) see n_face = 0 there,
// hence zero flux.
#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/offsets.hpp"
#include "kernels/solid_transport.hpp"

namespace eulerfsi::kernels {

// Smoothing of psi before the normals are taken: the (1 2 1)^3 / 64 filter
//   s(i,j,k) = sum_{a,b,c in -1..1} w_a w_b w_c psi(i+a, j+b, k+c),  w_0 = 1/2, w_(+-1) = 1/4
inline void smooth_121(const Field3& out, const Field3& psi, const Box& box) {
  for_each_cell("eulerfsi::solid::smooth_psi", box, KOKKOS_LAMBDA(int i, int j, int k) {
    double s = 0.0;
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        for (int c = -1; c <= 1; ++c) {
          const double w = (a == 0 ? 0.5 : 0.25) * (b == 0 ? 0.5 : 0.25) * (c == 0 ? 0.5 : 0.25);
          s += w * psi(i + a, j + b, k + c);
        }
    out(i, j, k) = s;
  });
}

constexpr double kNormalCutoff = 1e-2;

// n = g / |g| where |g| h >= kNormalCutoff, else 0,  g_D = (psi(c + e_D) - psi(c - e_D)) / (2 h_D)  at cell centres;
// n = 0 exactly where psi is flat.
inline void interface_normals(const Field3& nx, const Field3& ny, const Field3& nz, const Field3& psi, const double h[3],
                              const Box& box) {
  const double ix = 0.5 / h[0], iy = 0.5 / h[1], iz = 0.5 / h[2];
  const double hmin = compat::fmin(h[0], compat::fmin(h[1], h[2]));
  for_each_cell("eulerfsi::solid::normals", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double gx = (psi(i + 1, j, k) - psi(i - 1, j, k)) * ix;
    const double gy = (psi(i, j + 1, k) - psi(i, j - 1, k)) * iy;
    const double gz = (psi(i, j, k + 1) - psi(i, j, k - 1)) * iz;
    const double g = compat::sqrt(gx * gx + gy * gy + gz * gz);
    // away from the interface (psi changes by < 1 % per cell: psi < 0.005 or > 0.995 on the
    // equilibrium profile) n = 0: the normals of the round-off/WENO noise there are random, and
    // compression along them gathers the noise into spurious blobs (no tangential diffusion
    // damps it, unlike the isotropic form)
    const double inv = g * hmin < kNormalCutoff ? 0.0 : 1.0 / g;
    nx(i, j, k) = gx * inv;
    ny(i, j, k) = gy * inv;
    nz(i, j, k) = gz * inv;
  });
}

// Central difference of psi along T averaged over the two cells of the face c | c + e_D:
//   (d psi / d x_T)_face = [psi(c+T) - psi(c-T) + psi(c+D+T) - psi(c+D-T)] / (4 h_T)
template <int D, int T>
KOKKOS_FORCEINLINE_FUNCTION double transverse_gradient(const Field3& psi, double inv_4h, int i, int j, int k) {
  return (shifted<T>(psi, i, j, k, 1) - shifted<T>(psi, i, j, k, -1) + shifted<D, T>(psi, i, j, k, 1, 1) -
          shifted<D, T>(psi, i, j, k, 1, -1)) *
         inv_4h;
}

template <int C>
KOKKOS_FORCEINLINE_FUNCTION const Field3& component(const Field3& nx, const Field3& ny, const Field3& nz) {
  if constexpr (C == 0) return nx;
  else if constexpr (C == 1) return ny;
  else return nz;
}

KOKKOS_FORCEINLINE_FUNCTION bool normal_is_zero(const Field3& nx, const Field3& ny, const Field3& nz, int i, int j,
                                                int k) {
  return nx(i, j, k) == 0.0 && ny(i, j, k) == 0.0 && nz(i, j, k) == 0.0;
}

// Face flux of the OKZ equation between cell c and its +D neighbour:
//   n_f = (n_c + n_{c+D}) / 2   (per component, not renormalised)
//   (grad psi . n)_f = n_f,D (psi_{c+D} - psi_c) / h_D + sum_{T != D} n_f,T (d psi / d x_T)_face
//   F_D = [psi (1 - psi)]_f n_f,D - eps (grad psi . n)_f n_f,D,
//   [psi (1 - psi)]_f = [psi_c (1 - psi_c) + psi_{c+D} (1 - psi_{c+D})] / 2
// (the upwind-bounded psi_up (1 - psi_down) was tried: it elongates a resting ellipsoid by 10 %
// over 40 h of pseudo-time, the mean of the products by 0.04 % with smoothed normals).
template <int D>
KOKKOS_FORCEINLINE_FUNCTION double okz_flux(const Field3& psi, const Field3& nx, const Field3& ny, const Field3& nz,
                                            double eps, const double inv_h[3], int i, int j, int k) {
  constexpr int T1 = (D + 1) % 3, T2 = (D + 2) % 3;
  const Field3& mD = component<D>(nx, ny, nz);
  const Field3& m1 = component<T1>(nx, ny, nz);
  const Field3& m2 = component<T2>(nx, ny, nz);
  const double nD = 0.5 * (mD(i, j, k) + shifted<D>(mD, i, j, k, 1));
  if (nD == 0.0) return 0.0;
  const double n1 = 0.5 * (m1(i, j, k) + shifted<D>(m1, i, j, k, 1));
  const double n2 = 0.5 * (m2(i, j, k) + shifted<D>(m2, i, j, k, 1));
  const double p0 = psi(i, j, k), p1 = shifted<D>(psi, i, j, k, 1);
  const double gn = nD * (p1 - p0) * inv_h[D] + n1 * transverse_gradient<D, T1>(psi, 0.25 * inv_h[T1], i, j, k) +
                    n2 * transverse_gradient<D, T2>(psi, 0.25 * inv_h[T2], i, j, k);
  return (0.5 * (p0 * (1.0 - p0) + p1 * (1.0 - p1)) - eps * gn) * nD;
}

// rhs = -div F = -sum_D (F_D(c) - F_D(c - e_D)) / h_D. Every face flux carries the factor n_f,D,
// so a cell whose normal and whose six neighbours' normals are all zero has six zero fluxes:
// skipped (exactly what its neighbours compute for the shared faces, so conservation holds).
inline void sharpening_rhs(const Field3& rhs, const Field3& psi, const Field3& nx, const Field3& ny, const Field3& nz,
                           double eps, const double h[3], const Box& box) {
  const double inv_h[3] = {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]};
  const double ix = inv_h[0], iy = inv_h[1], iz = inv_h[2];
  for_each_cell("eulerfsi::solid::sharpen_rhs", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double ih[3] = {ix, iy, iz};
    if (normal_is_zero(nx, ny, nz, i, j, k) && normal_is_zero(nx, ny, nz, i - 1, j, k) &&
        normal_is_zero(nx, ny, nz, i + 1, j, k) && normal_is_zero(nx, ny, nz, i, j - 1, k) &&
        normal_is_zero(nx, ny, nz, i, j + 1, k) && normal_is_zero(nx, ny, nz, i, j, k - 1) &&
        normal_is_zero(nx, ny, nz, i, j, k + 1)) {
      rhs(i, j, k) = 0.0;
      return;
    }
    rhs(i, j, k) =
        -((okz_flux<0>(psi, nx, ny, nz, eps, ih, i, j, k) - okz_flux<0>(psi, nx, ny, nz, eps, ih, i - 1, j, k)) * ix +
          (okz_flux<1>(psi, nx, ny, nz, eps, ih, i, j, k) - okz_flux<1>(psi, nx, ny, nz, eps, ih, i, j - 1, k)) * iy +
          (okz_flux<2>(psi, nx, ny, nz, eps, ih, i, j, k) - okz_flux<2>(psi, nx, ny, nz, eps, ih, i, j, k - 1)) * iz);
  });
}

// The rhs of one sharpening step as the solver takes it: psi smoothed once by (1 2 1)^3 / 64 into
// `smooth` (on box + 2), normals from it (box + 1), face fluxes from psi itself (box). psi must be
// valid on box + 3 (the ghosts). Normals from the raw psi, whose edge is 2-3 cells wide, carry
// O(1) errors at the tips of a deformed particle and the compression along them drifts the shape
// (an ellipsoid D 0.19 elongates by 2.6 % over 40 h of pseudo-time, by 0.04 % with the smoothing).
inline void sharpening_step_rhs(const Field3& rhs, const Field3& psi, const Field3& smooth, const Field3& nx,
                                const Field3& ny, const Field3& nz, double eps, const double h[3], const Box& box) {
  const Box g1{{box.lo[0] - 1, box.lo[1] - 1, box.lo[2] - 1}, {box.hi[0] + 1, box.hi[1] + 1, box.hi[2] + 1}};
  const Box g2{{box.lo[0] - 2, box.lo[1] - 2, box.lo[2] - 2}, {box.hi[0] + 2, box.hi[1] + 2, box.hi[2] + 2}};
  smooth_121(smooth, psi, g2);
  interface_normals(nx, ny, nz, smooth, h, g1);
  sharpening_rhs(rhs, psi, nx, ny, nz, eps, h, box);
}

// The isotropic form of Olsson & Kreiss 2005, for comparison (tests): face flux
//   F_D = [psi (1 - psi)]_f n_f,D - eps (psi_{c+D} - psi_c) / h_D
template <int D>
KOKKOS_FORCEINLINE_FUNCTION double isotropic_flux(const Field3& psi, const Field3& nD, double eps_over_h, int i, int j,
                                                  int k) {
  const double p0 = psi(i, j, k), p1 = shifted<D>(psi, i, j, k, 1);
  const double compress = 0.5 * (p0 * (1.0 - p0) + p1 * (1.0 - p1)) * 0.5 * (nD(i, j, k) + shifted<D>(nD, i, j, k, 1));
  return compress - eps_over_h * (p1 - p0);
}

// rhs = -div F of the isotropic form (cells far from any interface: exactly zero, skipped).
inline void sharpening_rhs_isotropic(const Field3& rhs, const Field3& psi, const Field3& nx, const Field3& ny,
                                     const Field3& nz, double eps, const double h[3], const Box& box) {
  const double ex = eps / h[0], ey = eps / h[1], ez = eps / h[2];
  const double ix = 1.0 / h[0], iy = 1.0 / h[1], iz = 1.0 / h[2];
  for_each_cell("eulerfsi::solid::sharpen_rhs_iso", box, KOKKOS_LAMBDA(int i, int j, int k) {
    if (star_max(psi, i, j, k) == 0.0) {
      rhs(i, j, k) = 0.0;
      return;
    }
    rhs(i, j, k) = -((isotropic_flux<0>(psi, nx, ex, i, j, k) - isotropic_flux<0>(psi, nx, ex, i - 1, j, k)) * ix +
                     (isotropic_flux<1>(psi, ny, ey, i, j, k) - isotropic_flux<1>(psi, ny, ey, i, j - 1, k)) * iy +
                     (isotropic_flux<2>(psi, nz, ez, i, j, k) - isotropic_flux<2>(psi, nz, ez, i, j, k - 1)) * iz);
  });
}

}  // namespace eulerfsi::kernels
