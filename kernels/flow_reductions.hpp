#pragma once
// Local (this rank's) reductions over owned cells for the flow diagnostics; the driver sums
// or maxes them across ranks.
#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/time_update.hpp"

namespace eulerfsi::kernels {

// max over cells of |div_h u|
inline double max_abs_divergence(const Field3& u, const Field3& v, const Field3& w, const double h[3], const Box& box) {
  const double ix = 1.0 / h[0], iy = 1.0 / h[1], iz = 1.0 / h[2];
  double result = 0.0;
  reduce_cells("eulerfsi::diag::max_div", box, KOKKOS_LAMBDA(int i, int j, int k, double& m) {
    const double d = (u(i, j, k) - u(i - 1, j, k)) * ix + (v(i, j, k) - v(i, j - 1, k)) * iy +
                     (w(i, j, k) - w(i, j, k - 1)) * iz;
    m = compat::fmax(m, compat::fabs(d));
  }, Kokkos::Max<double>(result));
  return result;
}

// The signal rate of one cell: max over directions of (|u_D| + c) / h_D, NaN and Inf mapped to the
// largest double so that a blow-up is seen by the maximum (NaN compares false).
struct SignalRate {
  Field3 u, v, w;
  double ix, iy, iz, c;

  KOKKOS_INLINE_FUNCTION static double rate(double a, double b, double d, double c, double ix, double iy, double iz) {
    const double r = compat::fmax((compat::fabs(a) + c) * ix, compat::fmax((compat::fabs(b) + c) * iy, (compat::fabs(d) + c) * iz));
    return r <= 1e300 ? r : 1e308;
  }
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, double& m) const {
    m = compat::fmax(m, rate(u(i, j, k), v(i, j, k), w(i, j, k), c, ix, iy, iz));
  }
  // host: the row's maximum in kLanes running maxima, so the loop vectorises
  double row_reduce(int i, int j, int k0, int k1) const {
    constexpr int kLanes = 8;
    const double* KOKKOS_RESTRICT ur = &u(i, j, 0);
    const double* KOKKOS_RESTRICT vr = &v(i, j, 0);
    const double* KOKKOS_RESTRICT wr = &w(i, j, 0);
    double lane[kLanes] = {};
    int k = k0;
    for (; k + kLanes <= k1; k += kLanes)
      for (int l = 0; l < kLanes; ++l) {
        const double r = rate(ur[k + l], vr[k + l], wr[k + l], c, ix, iy, iz);
        lane[l] = r > lane[l] ? r : lane[l];
      }
    for (int l = 0; k < k1; ++k, ++l) {
      const double r = rate(ur[k], vr[k], wr[k], c, ix, iy, iz);
      lane[l] = r > lane[l] ? r : lane[l];
    }
    double m = 0.0;
    for (int l = 0; l < kLanes; ++l) m = lane[l] > m ? lane[l] : m;
    return m;
  }
};

// max over faces and directions of (|u_D| + c) / h_D: the CFL number per unit time step,
// with c the fastest elastic wave speed sqrt(G) (0 without solids)
inline double max_signal_rate(const Field3& u, const Field3& v, const Field3& w, const double h[3], double c,
                              const Box& box) {
  double result = 0.0;
  reduce_rows("eulerfsi::diag::cfl", box, SignalRate{u, v, w, 1.0 / h[0], 1.0 / h[1], 1.0 / h[2], c},
              Kokkos::Max<double>(result));
  return result;
}

// An x-face's share of the flow rate: 1 - chi_u (1 without a mask).
KOKKOS_INLINE_FUNCTION double open_weight(const Mask2& chi_u, bool has_mask, int j, int k) {
  return has_mask ? 1.0 - chi_u(j, k) : 1.0;
}

// Sum of u over x-faces open to the flow (chi = 0): the flow rate Q times Nx / (dy dz).
inline double open_face_sum(const Field3& u, const Mask2& chi_u, const Box& box) {
  const bool has_mask = chi_u.extent(0) > 0;
  double s = 0.0;
  reduce_cells("eulerfsi::diag::flow_rate", box, KOKKOS_LAMBDA(int i, int j, int k, double& su) {
    su += open_weight(chi_u, has_mask, j, k) * u(i, j, k);
  }, Kokkos::Sum<double>(s));
  return s;
}

// u(i,j,k) += du open(j,k) (du everywhere without a mask): x-independent, so div u is untouched
inline void add_open_x_velocity(const Field3& u, const Mask2& open_u, double du, const Box& box) {
  const bool has_mask = open_u.extent(0) > 0;
  for_each_cell("eulerfsi::flow_rate::correct", box, KOKKOS_LAMBDA(int i, int j, int k) {
    u(i, j, k) += has_mask ? du * open_u(j, k) : du;
  });
}

// sum over faces of ((u + u_frame)^2 + v^2 + w^2) / 2: the laboratory's kinetic energy
inline double kinetic_energy_sum(const Field3& u, const Field3& v, const Field3& w, const Box& box,
                                 double u_frame = 0.0) {
  double result = 0.0;
  reduce_cells("eulerfsi::diag::kinetic_energy", box,
                          KOKKOS_LAMBDA(int i, int j, int k, double& s) {
    const double ul = u(i, j, k) + u_frame;
    s += 0.5 * (ul * ul + v(i, j, k) * v(i, j, k) + w(i, j, k) * w(i, j, k));
  }, Kokkos::Sum<double>(result));
  return result;
}

// max |f| and whether any value is not finite, for the blow-up guard
inline bool all_finite(const Field3& f, const Box& box) {
  int bad = 0;
  reduce_cells("eulerfsi::diag::finite", box, KOKKOS_LAMBDA(int i, int j, int k, int& b) {
    if (!compat::isfinite(f(i, j, k))) b += 1;
  }, Kokkos::Sum<int>(bad));
  return bad == 0;
}

}  // namespace eulerfsi::kernels
