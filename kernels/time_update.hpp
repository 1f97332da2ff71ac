#pragma once
// The wall parts of the RK3 predictor: the masks, the second-order wall layer, and the implicit
// viscosity's right-hand side. The explicit predictor itself, u* = [u^k + dt (gamma rhs^k + zeta
// rhs^(k-1)) + pen u_wall] / (1 + pen) with pen = alpha dt chi / eta (Kadoch et al. 2012; chi(j,k) the
// x-independent wall mask at the component's staggered location), runs inside the momentum pass
// (kernels/momentum_predictor.hpp, kernels/predictor_terms.hpp).
#include "core/launch.hpp"
#include "core/types.hpp"

namespace eulerfsi::kernels {

using Mask2 = Kokkos::View<double**, Kokkos::LayoutRight, MemSpace>;
using Offset2 = Kokkos::View<int**[2], Kokkos::LayoutRight, MemSpace>;
using WallLayer = Kokkos::View<int* [2], Kokkos::LayoutRight, MemSpace>;

// The second-order pipe wall: the same implicit penalization, but towards a target that puts the
// zero of (u - u_wall) on the circle. On the first fluid layer (Fadlun et al. 2000 style direct
// forcing) the target is the linear interpolation between the wall, at distance t along a grid
// line, and the fluid point (j, k) + off one cell further in:
//   u <- (u + pen u_t) / (1 + pen),  u_t = w u(i, j + off_y, k + off_z) + (1 - w) u_wall,  w = t / (t + h)
// Outside the pipe (u_t = u_wall) the predictor does it with the mask chi_wall; this runs after it on
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

// The implicit viscosity (time.implicit_viscosity; RK3 with Crank-Nicolson on the constant mu_f
// part, as CaNS does: Costa 2018, Comput. Math. Appl. 76): the predictor solves
//   (I - c L_h) u* = u^k + dt (gamma rhs^k + zeta rhs^(k-1)) + c L_h u^k,   c = alpha dt mu_f / 2,
// rhs without the mu_f part. This writes the right-hand side into w (7-point L_h, ghosts of u
// filled at the substep's start).
// c L_h u at (i, j, k) with the per-direction weights cx = c / h_x^2, ... (7-point stencil).
KOKKOS_FORCEINLINE_FUNCTION double scaled_laplacian(const Field3& u, double cx, double cy, double cz, int i, int j,
                                                    int k) {
  const double uc = u(i, j, k);
  return cx * (u(i + 1, j, k) - 2.0 * uc + u(i - 1, j, k)) + cy * (u(i, j + 1, k) - 2.0 * uc + u(i, j - 1, k)) +
         cz * (u(i, j, k + 1) - 2.0 * uc + u(i, j, k - 1));
}

inline void implicit_viscosity_rhs(const Field3& w, const Field3& u, const Field3& rhs_new, const Field3& rhs_old,
                                   double dt, double gamma, double zeta, double c, const double h[3], const Box& box) {
  const double a = dt * gamma, b = dt * zeta;
  const double cx = c / (h[0] * h[0]), cy = c / (h[1] * h[1]), cz = c / (h[2] * h[2]);
  for_each_cell("eulerfsi::rk3::implicit_viscosity_rhs", box, KOKKOS_LAMBDA(int i, int j, int k) {
    w(i, j, k) = u(i, j, k) + a * rhs_new(i, j, k) + b * rhs_old(i, j, k) + scaled_laplacian(u, cx, cy, cz, i, j, k);
  });
}

// The wall's velocity in the implicit half: L_h u* next to a wall reads the ghost 2 u_wall - u*(0),
// i.e. the homogeneous operator of the solver plus 2 u_wall / h^2, moved to the right-hand side:
//   w(first cell) += c 2 u_wall / h_dir^2   on both walls across `dir` (storage planes of `box`).
inline void add_wall_velocity_term(const Field3& w, int dir, int n_interior, double coef_lo, double coef_hi,
                                   const Box& box) {
  Box plane = box;
  plane.lo[dir] = 0;
  plane.hi[dir] = 1;
  const int lo = kGhost, hi = kGhost + n_interior - 1;
  const int sj = dir == 1, sk = dir == 2;
  for_each_cell("eulerfsi::rk3::wall_velocity_term", plane, KOKKOS_LAMBDA(int i, int j, int k) {
    const int j0 = j * (1 - sj), k0 = k * (1 - sk);
    w(i, j0 + sj * lo, k0 + sk * lo) += coef_lo;
    w(i, j0 + sj * hi, k0 + sk * hi) += coef_hi;
  });
}

// The pipe wall with the implicit viscosity: the penalization acts on an explicit estimate of the
// predicted velocity, u~ = w + c L_h u (explicit Euler on the whole viscous term), and what it
// changes there is added to the right-hand side w before the solve (the direct forcing of
// Fadlun et al. 2000 taken into the implicit step). At a steady state this leaves the forced
// points exactly at their targets and the fluid on the steady discrete equations; penalizing
// after the solve instead moved the steady pipe's dp/dx by 7 % at 24 explicit limits per step.
//   w += (u~ + pen u_t) / (1 + pen) - u~,   pen = alpha dt chi / eta,   u_t = u_wall
KOKKOS_INLINE_FUNCTION double explicit_estimate(const Field3& w, const Field3& u, double cx, double cy, double cz,
                                                int i, int j, int k) {
  return w(i, j, k) + scaled_laplacian(u, cx, cy, cz, i, j, k);
}

inline void force_implicit_wall(const Field3& w, const Field3& u, const Mask2& chi, double penal_factor, double u_wall,
                                double c, const double h[3], const Box& box, const char* label) {
  if (chi.extent(0) == 0) return;
  const double cx = c / (h[0] * h[0]), cy = c / (h[1] * h[1]), cz = c / (h[2] * h[2]);
  for_each_cell(label, box, KOKKOS_LAMBDA(int i, int j, int k) {
    if (chi(j, k) == 0.0) return;
    const double pen = penal_factor * chi(j, k);
    const double est = explicit_estimate(w, u, cx, cy, cz, i, j, k);
    w(i, j, k) += (est + pen * u_wall) / (1.0 + pen) - est;
  });
}

// The interpolated wall's first layer the same way, towards u_t = wt u~(neighbour) + (1 - wt) u_wall
// (penalize_wall_layer's target, on the estimate). The neighbour is never on the layer or in the
// mask, so its w is not changed by this pass or the one before.
inline void force_implicit_wall_layer(const Field3& w, const Field3& u, const WallLayer& layer, const Mask2& wt,
                                      const Offset2& off, double penal_factor, double u_wall, double c,
                                      const double h[3], const Box& box, const char* label) {
  const int points = int(layer.extent(0));
  if (points == 0) return;
  const double cx = c / (h[0] * h[0]), cy = c / (h[1] * h[1]), cz = c / (h[2] * h[2]);
  Kokkos::parallel_for(label, Policy2({box.lo[0], 0}, {box.hi[0], points}), KOKKOS_LAMBDA(int i, int n) {
    const int j = layer(n, 0), k = layer(n, 1);
    const int jn = j + off(j, k, 0), kn = k + off(j, k, 1);
    const double est = explicit_estimate(w, u, cx, cy, cz, i, j, k);
    const double target = wt(j, k) * explicit_estimate(w, u, cx, cy, cz, i, jn, kn) + (1.0 - wt(j, k)) * u_wall;
    w(i, j, k) += (est + penal_factor * target) / (1.0 + penal_factor) - est;
  });
}

}  // namespace eulerfsi::kernels
