#pragma once
// Diagnostics of one soft body: psi-weighted volume integrals over this rank's cells. Each
// quantity is its own parallel_reduce with one Sum<double> (robust on Kokkos 3.4 and 4.x); the
// caller MPI-sums the plain structs (they are arrays of doubles) and finishes on the host.
#include <cmath>

#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/momentum.hpp"
#include "kernels/offsets.hpp"
#include "kernels/elastic_force.hpp"
#include "kernels/solid_fields.hpp"
#include "kernels/solid_transport.hpp"

namespace eulerfsi::kernels {

// First moments, all multiplied by dV:
//   volume = sum psi, y = sum psi y, z = sum psi z, cos/sin = sum psi cos|sin(2 pi x / Lx),
//   u, v, w = sum psi u_c (face velocities averaged to the centre).
struct BodyFirstMoments {
  enum { Volume, Y, Z, Cos, Sin, U, V, W, Count };
  double s[Count];
};
// Moments about a reference point c (minimum image in the periodic directions), times dV:
//   m1_a = sum psi (x_a - c_a), m2 = sum psi (x_a - c_a)(x_b - c_b) in the order XX,YY,ZZ,XY,XZ,YZ.
// psi is the body's indicator smoothed by the cell box, so m2_aa exceeds the body's own moment by
// V h_a^2/12 (isotropic on a cubic mesh; subtract it for absolute moments).
struct BodySecondMoments {
  enum { Count = 9 };
  double m1[3];
  double m2[kTensorComponents];
};
// The paper's force decomposition (eq. force), psi-weighted, at cell centres, times dV:
//   P = -sum psi grad p, I = -sum psi div(u u), V = sum psi mu_s div(grad u + grad u^T),
//   E = sum psi G div(B - I).
struct BodyForces {
  enum { Count = 12 };
  double pressure[3], inertia[3], viscous[3], elastic[3];
};
// The body's momentum P = sum psi u_c dV and the forces that change it, each term as the solver
// discretises it (grid frame; P and dP/dt are the same in the laboratory, x being periodic):
//   dP/dt = sum psi du_c/dt + sum u_c dpsi/dt
//   pressure = -sum psi grad p;  inertia = -sum psi div(u u) + sum u_c dpsi/dt, with
//   dpsi/dt = -div^WENO(u psi) (the paper model's transport) or, where psi is derived (the
//   reference map), (psi - psi_step_start) / dt over the last step;
//   viscous = sum psi div(2 mu(psi) E), mu = mu_f + psi (mu_s - mu_f);
//   elastic = sum psi div[psi G ((B + B_prev)/2 - I)]   (the stress of the last substep)
// each face term averaged over the cell's two D-faces, as u_c is.
struct BodyMomentum {
  enum { Count = 15 };
  double momentum[3], pressure[3], inertia[3], viscous[3], elastic[3];
};

namespace detail {

template <class F>
inline double sum_over(const char* label, const Box& box, const F& f) {
  double r = 0.0;
  reduce_cells(label, box, f, Kokkos::Sum<double>(r));
  return r;
}

// x - c mapped to [-L/2, L/2) when the direction is periodic with period L (L = 0: not periodic).
KOKKOS_INLINE_FUNCTION double min_image(double d, double L) {
  if (L <= 0.0) return d;
  const double t = d / L + 0.5;
  long n = static_cast<long>(t);  // floor without a version-dependent Kokkos math call
  if (t < static_cast<double>(n)) n -= 1;
  return d - L * static_cast<double>(n);
}

// A cell's weight in the core moments. cut >= 0: psi where psi >= cut, else 0 (a transported
// psi's halo left out). cut < 0: psi times a C1 ramp from 0 at psi = |cut|/2 to 1 at 3|cut|/2, so
// a cell whose derived psi rises or falls through the cut moves the moments continuously.
KOKKOS_INLINE_FUNCTION double core_weight(double p, double cut) {
  if (cut >= 0.0) return p < cut ? 0.0 : p;
  const double t = (p + 0.5 * cut) / -cut;  // (p - |cut|/2) / |cut|
  if (t <= 0.0) return 0.0;
  if (t >= 1.0) return p;
  return p * t * t * (3.0 - 2.0 * t);
}

struct FirstMomentTerm {
  WindowField psi;
  Field3 u, v, w;
  CellCentres xc;
  double kx;  // 2 pi / Lx
  int what;
  double psi_min;  // the cut of core_weight
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, double& acc) const {
    const double p = core_weight(psi(i, j, k), psi_min);
    if (p == 0.0) return;
    double f = 1.0;
    switch (what) {
      case BodyFirstMoments::Y: f = xc(1, j); break;
      case BodyFirstMoments::Z: f = xc(2, k); break;
      case BodyFirstMoments::Cos: f = compat::cos(kx * xc(0, i)); break;
      case BodyFirstMoments::Sin: f = compat::sin(kx * xc(0, i)); break;
      case BodyFirstMoments::U: f = 0.5 * (u(i, j, k) + u(i - 1, j, k)); break;
      case BodyFirstMoments::V: f = 0.5 * (v(i, j, k) + v(i, j - 1, k)); break;
      case BodyFirstMoments::W: f = 0.5 * (w(i, j, k) + w(i, j, k - 1)); break;
      default: break;
    }
    acc += p * f;
  }
};

struct SecondMomentTerm {
  WindowField psi;
  CellCentres xc;
  double c[3], period[3];
  int what;  // 0..2: m1, 3..8: m2
  double psi_min;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, double& acc) const {
    const double p = core_weight(psi(i, j, k), psi_min);
    if (p == 0.0) return;
    const double d[3] = {min_image(xc(0, i) - c[0], period[0]), min_image(xc(1, j) - c[1], period[1]),
                         min_image(xc(2, k) - c[2], period[2])};
    const int ra[6] = {0, 1, 2, 0, 0, 1}, rb[6] = {0, 1, 2, 1, 2, 2};
    const double f = what < 3 ? d[what] : d[ra[what - 3]] * d[rb[what - 3]];
    acc += p * f;
  }
};

// div(u u_D) at the D-face between i and i + e_D, as in kernels/momentum.hpp.
template <int D, int E>
KOKKOS_FORCEINLINE_FUNCTION double advective_edge(const Velocity& vel, int i, int j, int k) {
  const Field3& uD = vel.c[D];
  const Field3& uE = vel.c[E];
  return 0.25 * (uD(i, j, k) + shifted<E>(uD, i, j, k, 1)) * (uE(i, j, k) + shifted<D>(uE, i, j, k, 1));
}
template <int D>
KOKKOS_FORCEINLINE_FUNCTION double advection_at_face(const Velocity& vel, const double inv_h[3], int i, int j, int k) {
  constexpr int E1 = (D + 1) % 3, E2 = (D + 2) % 3;
  const Field3& uD = vel.c[D];
  const double cp = 0.5 * (shifted<D>(uD, i, j, k, 1) + uD(i, j, k));
  const double cm = 0.5 * (uD(i, j, k) + shifted<D>(uD, i, j, k, -1));
  return (cp * cp - cm * cm) * inv_h[D] +
         (advective_edge<D, E1>(vel, i, j, k) -
          advective_edge<D, E1>(vel, i - Unit<E1>::i, j - Unit<E1>::j, k - Unit<E1>::k)) *
             inv_h[E1] +
         (advective_edge<D, E2>(vel, i, j, k) -
          advective_edge<D, E2>(vel, i - Unit<E2>::i, j - Unit<E2>::j, k - Unit<E2>::k)) *
             inv_h[E2];
}

// div(grad u + grad u^T)_D at the D-face, the viscous stencil of kernels/momentum.hpp with mu = 1.
template <int D, int E>
KOKKOS_FORCEINLINE_FUNCTION double strain_edge(const Velocity& vel, const double inv_h[3], int i, int j, int k) {
  const Field3& uD = vel.c[D];
  const Field3& uE = vel.c[E];
  return (shifted<E>(uD, i, j, k, 1) - uD(i, j, k)) * inv_h[E] + (shifted<D>(uE, i, j, k, 1) - uE(i, j, k)) * inv_h[D];
}
template <int D>
KOKKOS_FORCEINLINE_FUNCTION double viscous_at_face(const Velocity& vel, const double inv_h[3], int i, int j, int k) {
  constexpr int E1 = (D + 1) % 3, E2 = (D + 2) % 3;
  const Field3& uD = vel.c[D];
  const double sp = 2.0 * (shifted<D>(uD, i, j, k, 1) - uD(i, j, k)) * inv_h[D];
  const double sm = 2.0 * (uD(i, j, k) - shifted<D>(uD, i, j, k, -1)) * inv_h[D];
  return (sp - sm) * inv_h[D] +
         (strain_edge<D, E1>(vel, inv_h, i, j, k) -
          strain_edge<D, E1>(vel, inv_h, i - Unit<E1>::i, j - Unit<E1>::j, k - Unit<E1>::k)) *
             inv_h[E1] +
         (strain_edge<D, E2>(vel, inv_h, i, j, k) -
          strain_edge<D, E2>(vel, inv_h, i - Unit<E2>::i, j - Unit<E2>::j, k - Unit<E2>::k)) *
             inv_h[E2];
}

// One force term in direction D at the centre of cell (i,j,k), not yet weighted by psi.
// du_D/dx at the D-face (i,j,k), central: the extra advection U du_D/dx of a grid moving with U.
template <int D>
KOKKOS_FORCEINLINE_FUNCTION double ddx_at_face(const Velocity& vel, const double inv_h[3], int i, int j, int k) {
  return 0.5 * inv_h[0] * (vel.c[D](i + 1, j, k) - vel.c[D](i - 1, j, k));
}

// u_frame: the grid's x-velocity; the inertia term is the laboratory's, -div((u + u_frame e_x) u_D).
template <int D>
KOKKOS_INLINE_FUNCTION double force_term(int term, const Field3& p, const Velocity& vel, const Tensor6& b, double G,
                                         double mu_s, double u_frame, const double inv_h[3], int i, int j, int k) {
  constexpr int di = Unit<D>::i, dj = Unit<D>::j, dk = Unit<D>::k;
  switch (term) {
    case 0:  // -dp/dx_D, central difference of cell-centre pressure
      return -0.5 * inv_h[D] * (p(i + di, j + dj, k + dk) - p(i - di, j - dj, k - dk));
    case 1:  // face terms averaged over the two D-faces of the cell
      return -0.5 * (advection_at_face<D>(vel, inv_h, i, j, k) + advection_at_face<D>(vel, inv_h, i - di, j - dj, k - dk) +
                     u_frame * (ddx_at_face<D>(vel, inv_h, i, j, k) + ddx_at_face<D>(vel, inv_h, i - di, j - dj, k - dk)));
    case 2:
      return 0.5 * mu_s *
             (viscous_at_face<D>(vel, inv_h, i, j, k) + viscous_at_face<D>(vel, inv_h, i - di, j - dj, k - dk));
    default: {  // G d(B_DE)/dx_E by central differences (I is divergence free)
      double s = 0.0;
      for (int e = 0; e < 3; ++e) {
        const WindowField& bde = b.c[tensor_index(D, e)];
        const int ei = e == 0, ej = e == 1, ek = e == 2;
        s += 0.5 * inv_h[e] * (bde(i + ei, j + ej, k + ek) - bde(i - ei, j - ej, k - ek));
      }
      return G * s;
    }
  }
}

struct ForceTerm {
  WindowField psi;
  Field3 p;
  Velocity vel;
  Tensor6 b;
  double G, mu_s, u_frame;
  double inv_h[3];
  int term, dir;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, double& acc) const {
    const double w = psi(i, j, k);
    if (w == 0.0) return;  // most of the domain: skip the stencils
    const double f = dir == 0   ? force_term<0>(term, p, vel, b, G, mu_s, u_frame, inv_h, i, j, k)
                     : dir == 1 ? force_term<1>(term, p, vel, b, G, mu_s, u_frame, inv_h, i, j, k)
                                : force_term<2>(term, p, vel, b, G, mu_s, u_frame, inv_h, i, j, k);
    acc += w * f;
  }
};

// mu = mu_f + psi dmu at a cell centre, and its four-cell average on the D-E edge.
KOKKOS_INLINE_FUNCTION double mixture_mu(const WindowField& psi, double mu_f, double dmu, int a, int b, int c) {
  return mu_f + dmu * psi(a, b, c);
}
template <int D, int E>
KOKKOS_INLINE_FUNCTION double mixture_mu_edge(const WindowField& psi, double mu_f, double dmu, int a, int b, int c) {
  constexpr int di = Unit<D>::i, dj = Unit<D>::j, dk = Unit<D>::k, ei = Unit<E>::i, ej = Unit<E>::j, ek = Unit<E>::k;
  return 0.25 * (mixture_mu(psi, mu_f, dmu, a, b, c) + mixture_mu(psi, mu_f, dmu, a + di, b + dj, c + dk) +
                 mixture_mu(psi, mu_f, dmu, a + ei, b + ej, c + ek) +
                 mixture_mu(psi, mu_f, dmu, a + di + ei, b + dj + ej, c + dk + ek));
}

// div(2 mu E)_D at the D-face with the mixture viscosity mu = mu_f + psi dmu at cell centres and
// the four-cell average on edges: the viscous stencil of kernels/momentum.hpp.
template <int D>
KOKKOS_INLINE_FUNCTION double mixture_viscous_at_face(const Velocity& vel, const WindowField& psi, double mu_f, double dmu,
                                                      const double inv_h[3], int i, int j, int k) {
  constexpr int E1 = (D + 1) % 3, E2 = (D + 2) % 3;
  const Field3& uD = vel.c[D];
  const double sp = 2.0 * mixture_mu(psi, mu_f, dmu, i + Unit<D>::i, j + Unit<D>::j, k + Unit<D>::k) *
                    (shifted<D>(uD, i, j, k, 1) - uD(i, j, k)) * inv_h[D];
  const double sm =
      2.0 * mixture_mu(psi, mu_f, dmu, i, j, k) * (uD(i, j, k) - shifted<D>(uD, i, j, k, -1)) * inv_h[D];
  constexpr int a1 = Unit<E1>::i, b1 = Unit<E1>::j, c1 = Unit<E1>::k;
  constexpr int a2 = Unit<E2>::i, b2 = Unit<E2>::j, c2 = Unit<E2>::k;
  return (sp - sm) * inv_h[D] +
         (mixture_mu_edge<D, E1>(psi, mu_f, dmu, i, j, k) * strain_edge<D, E1>(vel, inv_h, i, j, k) -
          mixture_mu_edge<D, E1>(psi, mu_f, dmu, i - a1, j - b1, k - c1) *
              strain_edge<D, E1>(vel, inv_h, i - a1, j - b1, k - c1)) *
             inv_h[E1] +
         (mixture_mu_edge<D, E2>(psi, mu_f, dmu, i, j, k) * strain_edge<D, E2>(vel, inv_h, i, j, k) -
          mixture_mu_edge<D, E2>(psi, mu_f, dmu, i - a2, j - b2, k - c2) *
              strain_edge<D, E2>(vel, inv_h, i - a2, j - b2, k - c2)) *
             inv_h[E2];
}

// One term of BodyMomentum in direction D at cell (i,j,k), psi weight included.
// psi0, inv_dt: psi at the last step's start and 1 / its dt where dpsi/dt is psi's change over
// that step (step_difference), else unused.
template <int D>
KOKKOS_INLINE_FUNCTION double momentum_term(int term, const WindowField& psi, const Field3& p, const Velocity& vel,
                                            const Tensor6& b, const Tensor6& bp, double G, double mu_f, double dmu,
                                            const WindowField& psi0, double inv_dt, bool step_difference,
                                            const double inv_h[3], int i, int j, int k) {
  constexpr int di = Unit<D>::i, dj = Unit<D>::j, dk = Unit<D>::k;
  const double w = psi(i, j, k);
  const double uc = 0.5 * (vel.c[D](i, j, k) + vel.c[D](i - di, j - dj, k - dk));
  switch (term) {
    case 0: return w * uc;
    case 1: return w * force_term<D>(0, p, vel, b, G, 0.0, 0.0, inv_h, i, j, k);
    case 2: {
      // the transport of psi carries momentum in and out: u_c dpsi/dt, as psi actually changes
      const double dpsi = step_difference             ? (w - psi0(i, j, k)) * inv_dt
                          : star_max(psi, i, j, k) == 0.0 ? 0.0
                                                        : -weno_divergence(psi, vel.c[0], vel.c[1], vel.c[2], inv_h, i, j, k);
      return (w == 0.0 ? 0.0 : w * force_term<D>(1, p, vel, b, G, 0.0, 0.0, inv_h, i, j, k)) + uc * dpsi;
    }
    case 3:
      return w == 0.0 ? 0.0
                      : 0.5 * w *
                            (mixture_viscous_at_face<D>(vel, psi, mu_f, dmu, inv_h, i, j, k) +
                             mixture_viscous_at_face<D>(vel, psi, mu_f, dmu, inv_h, i - di, j - dj, k - dk));
    default:
      return w == 0.0 ? 0.0
                      : 0.5 * w *
                            (elastic_force_at_face<D>(psi, b, bp, ShearFromB{psi, b, bp, G}, G, inv_h, i, j, k) +
                             elastic_force_at_face<D>(psi, b, bp, ShearFromB{psi, b, bp, G}, G, inv_h, i - di, j - dj,
                                                      k - dk));
  }
}

struct MomentumTerm {
  WindowField psi;
  Field3 p;
  Velocity vel;
  Tensor6 b, bp;
  double G, mu_f, dmu;
  WindowField psi0;
  double inv_dt;
  bool step_difference;
  double inv_h[3];
  int term, dir;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, double& acc) const {
    acc += dir == 0   ? momentum_term<0>(term, psi, p, vel, b, bp, G, mu_f, dmu, psi0, inv_dt, step_difference, inv_h, i, j, k)
           : dir == 1 ? momentum_term<1>(term, psi, p, vel, b, bp, G, mu_f, dmu, psi0, inv_dt, step_difference, inv_h, i, j, k)
                      : momentum_term<2>(term, psi, p, vel, b, bp, G, mu_f, dmu, psi0, inv_dt, step_difference, inv_h, i, j, k);
  }
};

}  // namespace detail

// First moments of psi over `box` (owned cells), each times dV. Lx: periodic length in x. Cells
// with psi < psi_min are left out (the faint halo of numerical diffusion).
inline BodyFirstMoments body_first_moments(const WindowField& psi, const Velocity& vel, const CellCentres& xc, double Lx,
                                           const Box& box, double psi_min = 0.0) {
  const double dv = xc.h[0] * xc.h[1] * xc.h[2];
  BodyFirstMoments r{};
  for (int q = 0; q < BodyFirstMoments::Count; ++q) {
    detail::FirstMomentTerm f{psi, vel.c[0], vel.c[1], vel.c[2], xc, 2.0 * M_PI / Lx, q, psi_min};
    r.s[q] = dv * detail::sum_over("eulerfsi::diag::body_first_moments", box, f);
  }
  return r;
}

// The body's mean x-velocity sum psi u_c / sum psi as {sum psi, sum psi u_c} (times dV omitted).
// sum psi over the cells with psi >= psi_min (times dV omitted).
inline double body_volume(const WindowField& psi, const Box& box, double psi_min = 0.0) {
  const CellCentres none{{0, 0, 0}, {1, 1, 1}};
  const Field3 unused;  // the volume term reads no velocity
  detail::FirstMomentTerm volume{psi, unused, unused, unused, none, 0.0, BodyFirstMoments::Volume, psi_min};
  return detail::sum_over("eulerfsi::diag::body_volume", box, volume);
}

inline void body_x_momentum(const WindowField& psi, const Velocity& vel, const Box& box, double out[2],
                            double psi_min = 0.0) {
  const CellCentres none{{0, 0, 0}, {1, 1, 1}};
  detail::FirstMomentTerm momentum{psi, vel.c[0], vel.c[1], vel.c[2], none, 0.0, BodyFirstMoments::U, psi_min};
  out[0] = body_volume(psi, box, psi_min);
  out[1] = detail::sum_over("eulerfsi::diag::body_x_momentum", box, momentum);
}

// Moments about the point c; period[d] = domain length in a periodic direction, 0 otherwise.
inline BodySecondMoments body_second_moments(const WindowField& psi, const CellCentres& xc, const double c[3],
                                             const double period[3], const Box& box, double psi_min = 0.0) {
  const double dv = xc.h[0] * xc.h[1] * xc.h[2];
  BodySecondMoments r{};
  for (int q = 0; q < BodySecondMoments::Count; ++q) {
    detail::SecondMomentTerm f{psi, xc, {c[0], c[1], c[2]}, {period[0], period[1], period[2]}, q, psi_min};
    const double s = dv * detail::sum_over("eulerfsi::diag::body_second_moments", box, f);
    if (q < 3) r.m1[q] = s; else r.m2[q - 3] = s;
  }
  return r;
}

// Force terms of the paper's eq. (force) for one body, in the laboratory frame (u_frame: the grid's
// x-velocity; vel is relative to the grid); needs one ghost layer of p, u, B.
inline BodyForces body_forces(const WindowField& psi, const Field3& p, const Velocity& vel, const Tensor6& b, double G,
                              double mu_s, double u_frame, const double h[3], const Box& box) {
  const double dv = h[0] * h[1] * h[2];
  BodyForces r{};
  double* out[4] = {r.pressure, r.inertia, r.viscous, r.elastic};
  for (int term = 0; term < 4; ++term)
    for (int d = 0; d < 3; ++d) {
      detail::ForceTerm f{psi, p, vel, b, G, mu_s, u_frame, {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]}, term, d};
      out[term][d] = dv * detail::sum_over("eulerfsi::diag::body_forces", box, f);
    }
  return r;
}

// The body's momentum and the forces that change it (BodyMomentum), in the grid's frame; needs
// three ghost layers of psi (WENO) and one of p, u, B. psi_step_start (allocated: the map) and
// inv_dt: dpsi/dt from psi's change over the last step instead of the WENO transport.
inline BodyMomentum body_momentum(const WindowField& psi, const Field3& p, const Velocity& vel, const Tensor6& b,
                                  const Tensor6& b_prev, double G, double mu_f, double mu_s, const double h[3],
                                  const Box& box, const WindowField& psi_step_start = WindowField(),
                                  double inv_dt = 0.0) {
  const bool step_difference = psi_step_start.allocated();
  const double dv = h[0] * h[1] * h[2];
  BodyMomentum r{};
  double* out[5] = {r.momentum, r.pressure, r.inertia, r.viscous, r.elastic};
  for (int term = 0; term < 5; ++term)
    for (int d = 0; d < 3; ++d) {
      detail::MomentumTerm f{psi,     p,      vel, b, b_prev, G, mu_f, mu_s - mu_f, psi_step_start, inv_dt,
                             step_difference, {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]}, term, d};
      out[term][d] = dv * detail::sum_over("eulerfsi::diag::body_momentum", box, f);
    }
  return r;
}

// sum psi cos(2 pi x_d / L) and sum psi sin(2 pi x_d / L) over the box (times dV) for the periodic
// direction d = 1 or 2: the circular mean of a body that may straddle that direction's boundary
// (the plain mean of one that does lies half a period off).
inline void body_circular_moments(const WindowField& psi, const CellCentres& xc, int d, double L, const Box& box,
                                  double psi_min, double out[2]) {
  const double dv = xc.h[0] * xc.h[1] * xc.h[2], kd = 2.0 * M_PI / L;
  for (int q = 0; q < 2; ++q) {
    double s = 0.0;
    reduce_cells("eulerfsi::diag::body_circular_moments", box, KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
      const double p = detail::core_weight(psi(i, j, k), psi_min);
      if (p == 0.0) return;
      const double arg = kd * (d == 1 ? xc(1, j) : xc(2, k));
      acc += p * (q == 0 ? compat::cos(arg) : compat::sin(arg));
    }, Kokkos::Sum<double>(s));
    out[q] = s * dv;
  }
}

// Host: x-centroid as the circular mean of psi on the periodic x axis, in [0, Lx). Exact for a
// body symmetric about its centre; in general a reference point within the body from which
// body_second_moments' m1 gives the exact unwrapped centroid c = ref + m1 / volume (minimum image,
// valid while the body spans less than Lx/2 around ref).
inline double circular_mean_x(double cos_sum, double sin_sum, double Lx) {
  double x = std::atan2(sin_sum, cos_sum) * Lx / (2.0 * M_PI);
  if (x < 0.0) x += Lx;
  return x;
}

}  // namespace eulerfsi::kernels
