#pragma once
// Fractional-step projection on the MAC grid (Kim & Moin 1985):
//   L_h phi = div_h u* / (alpha dt),   u = u* - alpha dt grad_h phi
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/flow_reductions.hpp"

namespace eulerfsi::kernels {

// out(i,j,k) = scale * [ (u(i)-u(i-1))/dx + (v(j)-v(j-1))/dy + (w(k)-w(k-1))/dz ]
// out(i - shift, j - shift, k - shift) for a cell (i, j, k) of the box: shift = kGhost writes the
// interior as one contiguous block (a Poisson solver's own buffer, no copy in).
template <class Out>
inline void divergence_shifted(const Out& out, int shift, const Field3& u, const Field3& v, const Field3& w,
                               const double h[3], double scale, const Box& box) {
  const double ix = scale / h[0], iy = scale / h[1], iz = scale / h[2];
  for_each_cell("eulerfsi::projection::divergence", box, KOKKOS_LAMBDA(int i, int j, int k) {
    out(i - shift, j - shift, k - shift) = (u(i, j, k) - u(i - 1, j, k)) * ix + (v(i, j, k) - v(i, j - 1, k)) * iy +
                                           (w(i, j, k) - w(i, j, k - 1)) * iz;
  });
}

inline void divergence(const Field3& out, const Field3& u, const Field3& v, const Field3& w, const double h[3],
                       double scale, const Box& box) {
  divergence_shifted(out, 0, u, v, w, h, scale, box);
}

// The step's mean pressure: p_step = sum over substeps of alpha_s p_s (sum alpha_s = 1), so that
// the step's projections moved u by -dt grad p_step. first: the first substep starts the sum.
struct StepPressure {
  Field3 p_step;  // empty: not accumulated
  double alpha = 0.0;
  bool first = false;
};

// u_D(i) -= factor (phi(i + e_D) - phi(i)) / h_D for the three components in one sweep, and
// p_step += alpha phi on the same cells (phi is read there anyway; p_step's ghosts are the
// caller's to fill). Returns the sum over the x-faces open to the flow (chi_u = 0; every face
// without a mask) of the corrected u, kernels::open_face_sum's sum in the same order: the flow
// rate without a second read.
template <bool Accumulate>
inline double subtract_gradient_impl(const Field3& u, const Field3& v, const Field3& w, const Field3& phi,
                                     const double h[3], double factor, const Mask2& chi_u, const StepPressure& step,
                                     const Box& box) {
  const double ix = factor / h[0], iy = factor / h[1], iz = factor / h[2];
  const bool has_mask = chi_u.extent(0) > 0;
  const Field3 p_step = step.p_step;
  const double alpha = step.alpha;
  const bool first = step.first;
  double s = 0.0;
  reduce_cells("eulerfsi::projection::correct", box, KOKKOS_LAMBDA(int i, int j, int k, double& su) {
    const double p0 = phi(i, j, k);
    const double un = u(i, j, k) - (phi(i + 1, j, k) - p0) * ix;
    u(i, j, k) = un;
    v(i, j, k) -= (phi(i, j + 1, k) - p0) * iy;
    w(i, j, k) -= (phi(i, j, k + 1) - p0) * iz;
    // a plain if: nvcc cannot first-capture a variable inside if constexpr in a device lambda
    if (Accumulate) p_step(i, j, k) = (first ? 0.0 : p_step(i, j, k)) + alpha * p0;
    su += open_weight(chi_u, has_mask, j, k) * un;
  }, Kokkos::Sum<double>(s));
  return s;
}

inline double subtract_gradient(const Field3& u, const Field3& v, const Field3& w, const Field3& phi, const double h[3],
                                double factor, const Mask2& chi_u, const Box& box, const StepPressure& step = {}) {
  if (step.p_step.extent(0) > 0) return subtract_gradient_impl<true>(u, v, w, phi, h, factor, chi_u, step, box);
  return subtract_gradient_impl<false>(u, v, w, phi, h, factor, chi_u, step, box);
}

}  // namespace eulerfsi::kernels
