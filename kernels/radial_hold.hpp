#pragma once
// Holding a soft body's centroid in the cross-section (src/solid/radial_hold.hpp): a uniform
// acceleration over the body, u_D <- u_D + psi_D V_D for D = y, z, the psi-weighted face sums that
// choose V, and nothing else about the body (its deformation, its x-motion and spin stay free).
// The face of component D at (i, j, k) lies between cell (i, j, k) and the next cell along D; psi
// there is the mean of the two.
#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/momentum.hpp"
#include "kernels/particle_moments.hpp"
#include "kernels/solid_fields.hpp"

namespace eulerfsi::kernels {

// Per cross-section direction D = y, z (index D - 1), each times dV: mass = sum psi_D,
// square = sum psi_D^2, momentum = sum psi_D u_D, offset = sum psi_D (x_D - target_D).
struct RadialHoldSums {
  enum { Count = 8 };
  double mass[2], square[2], momentum[2], offset[2];
};

namespace detail {

struct RadialHoldTerm {
  WindowField psi;
  Field3 u;
  CellCentres xc;
  int comp;         // 1 (y) or 2 (z)
  double target;    // the held coordinate
  double period;    // 0 where the direction is not periodic
  int what;         // 0 mass, 1 square, 2 momentum, 3 offset
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, double& acc) const {
    const double p = 0.5 * (psi(i, j, k) + psi(i, j + (comp == 1), k + (comp == 2)));
    const int s = comp == 1 ? j : k;
    const double x = xc(comp, s) + 0.5 * xc.h[comp];
    acc += what == 0 ? p : what == 1 ? p * p : what == 2 ? p * u(i, j, k) : p * min_image(x - target, period);
  }
};

}  // namespace detail

// This rank's sums over the faces of `box` (the caller MPI-sums them).
inline RadialHoldSums radial_hold_sums(const WindowField& psi, const Velocity& vel, const CellCentres& xc,
                                       const double target[2], const double period[2], double dv, const Box& box) {
  RadialHoldSums s{};
  double* out[4][2] = {{&s.mass[0], &s.mass[1]}, {&s.square[0], &s.square[1]},
                       {&s.momentum[0], &s.momentum[1]}, {&s.offset[0], &s.offset[1]}};
  for (int d = 0; d < 2; ++d)
    for (int w = 0; w < 4; ++w)
      *out[w][d] = dv * detail::sum_over("eulerfsi::hold::sums", box,
                                         detail::RadialHoldTerm{psi, vel.c[d + 1], xc, d + 1, target[d], period[d], w});
  return s;
}

// u_D += psi_D V_D on the y and z faces of `box`: the impulse V_D mass_D per unit density.
inline void radial_hold_push(const Velocity& vel, const WindowField& psi, const double V[2], const Box& box) {
  for (int d = 0; d < 2; ++d) {
    const Field3 u = vel.c[d + 1];
    const double v = V[d];
    const int dj = d == 0, dk = d == 1;
    for_each_cell("eulerfsi::hold::push", box, KOKKOS_LAMBDA(int i, int j, int k) {
      u(i, j, k) += 0.5 * (psi(i, j, k) + psi(i, j + dj, k + dk)) * v;
    });
  }
}

}  // namespace eulerfsi::kernels
