#pragma once
// Low-storage RK3 substep with implicit volume penalization (Kadoch et al. 2012):
//   u* = [u^k + dt (gamma rhs^k + zeta rhs^(k-1)) + (alpha dt chi / eta) u_wall] / (1 + alpha dt chi / eta)
// chi(j,k) is the x-independent solid-wall mask at the component's staggered location.
#include "core/launch.hpp"
#include "core/types.hpp"

namespace eulerfsi::kernels {

using Mask2 = Kokkos::View<double**, Kokkos::LayoutRight, MemSpace>;
using Offset2 = Kokkos::View<int**[2], Kokkos::LayoutRight, MemSpace>;
using WallLayer = Kokkos::View<int* [2], Kokkos::LayoutRight, MemSpace>;

inline void rk3_update(const Field3& u, const Field3& rhs_new, const Field3& rhs_old, const Mask2& chi, double dt,
                       double gamma, double zeta, double penal_factor, const Box& box, const char* label,
                       double u_wall = 0.0) {
  // penal_factor = alpha dt / eta; chi empty means no penalization; u_wall: the wall's velocity
  const bool has_mask = chi.extent(0) > 0;
  const double a = dt * gamma, b = dt * zeta;
  for_each_cell(label, box, KOKKOS_LAMBDA(int i, int j, int k) {
    // raw pointers on the shared layout: no aliasing between the update and its inputs
    const long c = i * long(u.stride(0)) + j * long(u.stride(1)) + k;
    double* KOKKOS_RESTRICT pu = u.data();
    const double* KOKKOS_RESTRICT pn = rhs_new.data();
    const double* KOKKOS_RESTRICT po = rhs_old.data();
    const double pen = has_mask ? penal_factor * chi(j, k) : 0.0;
    pu[c] = (pu[c] + a * pn[c] + b * po[c] + pen * u_wall) / (1.0 + pen);
  });
}

// The second-order pipe wall: the same implicit penalization, but towards a target that puts the
// zero of (u - u_wall) on the circle. On the first fluid layer (Fadlun et al. 2000 style direct
// forcing) the target is the linear interpolation between the wall, at distance t along a grid
// line, and the fluid point (j, k) + off one cell further in:
//   u <- (u + pen u_t) / (1 + pen),  u_t = w u(i, j + off_y, k + off_z) + (1 - w) u_wall,  w = t / (t + h)
// Outside the pipe (u_t = u_wall) rk3_update does it with the mask chi_wall; this runs after it on
// the layer's points only (a list of (j, k), every x). The neighbour read is never penalized
// itself, so updating in place has no race.
inline void penalize_wall_layer(const Field3& u, const WallLayer& layer, const Mask2& w, const Offset2& off,
                                double penal_factor, const Box& box, const char* label, double u_wall = 0.0) {
  const int points = int(layer.extent(0));
  if (points == 0) return;
  Kokkos::parallel_for(label, Policy2({box.lo[0], 0}, {box.hi[0], points}), KOKKOS_LAMBDA(int i, int n) {
    const int j = layer(n, 0), k = layer(n, 1);
    const double target = w(j, k) * u(i, j + off(j, k, 0), k + off(j, k, 1)) + (1.0 - w(j, k)) * u_wall;
    u(i, j, k) = (u(i, j, k) + penal_factor * target) / (1.0 + penal_factor);
  });
}

}  // namespace eulerfsi::kernels
