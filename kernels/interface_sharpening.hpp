#pragma once
// Conservative interface sharpening (Olsson & Kreiss 2005, J. Comput. Phys. 210, 225): one
// pseudo-time step of
//   dpsi/dtau + div[ psi (1 - psi) n ] = div( eps grad psi ),   n = grad psi / |grad psi|
// counteracts the numerical diffusion of the WENO advection, which otherwise widens the edge of
// a particle without bound and leaves a halo of small psi in which B has no meaning. The
// equilibrium profile is psi = 1 / (1 + exp(-d / eps)) across the interface; the flux form keeps
// the volume to round-off, and the zero flux through walls keeps it inside the domain.
#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/solid_transport.hpp"

namespace eulerfsi::kernels {

// n = grad psi / |grad psi| at cell centres (central differences), zero where psi is flat.
inline void interface_normals(const Field3& nx, const Field3& ny, const Field3& nz, const Field3& psi, const double h[3],
                              const Box& box) {
  const double ix = 0.5 / h[0], iy = 0.5 / h[1], iz = 0.5 / h[2];
  for_each_cell("eulerfsi::solid::normals", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double gx = (psi(i + 1, j, k) - psi(i - 1, j, k)) * ix;
    const double gy = (psi(i, j + 1, k) - psi(i, j - 1, k)) * iy;
    const double gz = (psi(i, j, k + 1) - psi(i, j, k - 1)) * iz;
    const double inv = 1.0 / (compat::sqrt(gx * gx + gy * gy + gz * gz) + 1e-12);
    nx(i, j, k) = gx * inv;
    ny(i, j, k) = gy * inv;
    nz(i, j, k) = gz * inv;
  });
}

// Face flux of the sharpening equation between cell c and its +D neighbour:
//   F = [psi (1 - psi)]_face n_face - eps (psi_+ - psi) / h
template <int D>
KOKKOS_FORCEINLINE_FUNCTION double sharpening_flux(const Field3& psi, const Field3& nD, double eps_over_h, int i, int j,
                                                   int k) {
  const double p0 = psi(i, j, k), p1 = shifted<D>(psi, i, j, k, 1);
  const double compress = 0.5 * (p0 * (1.0 - p0) + p1 * (1.0 - p1)) * 0.5 * (nD(i, j, k) + shifted<D>(nD, i, j, k, 1));
  return compress - eps_over_h * (p1 - p0);
}

// rhs = -div F (cells far from any interface: exactly zero, skipped).
inline void sharpening_rhs(const Field3& rhs, const Field3& psi, const Field3& nx, const Field3& ny, const Field3& nz,
                           double eps, const double h[3], const Box& box) {
  const double ex = eps / h[0], ey = eps / h[1], ez = eps / h[2];
  const double ix = 1.0 / h[0], iy = 1.0 / h[1], iz = 1.0 / h[2];
  for_each_cell("eulerfsi::solid::sharpen_rhs", box, KOKKOS_LAMBDA(int i, int j, int k) {
    if (star_max(psi, i, j, k) == 0.0) {
      rhs(i, j, k) = 0.0;
      return;
    }
    rhs(i, j, k) = -((sharpening_flux<0>(psi, nx, ex, i, j, k) - sharpening_flux<0>(psi, nx, ex, i - 1, j, k)) * ix +
                     (sharpening_flux<1>(psi, ny, ey, i, j, k) - sharpening_flux<1>(psi, ny, ey, i, j - 1, k)) * iy +
                     (sharpening_flux<2>(psi, nz, ez, i, j, k) - sharpening_flux<2>(psi, nz, ez, i, j, k - 1)) * iz);
  });
}

}  // namespace eulerfsi::kernels
