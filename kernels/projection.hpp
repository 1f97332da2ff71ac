#pragma once
// Fractional-step projection on the MAC grid (Kim & Moin 1985):
//   L_h phi = div_h u* / (alpha dt),   u = u* - alpha dt grad_h phi
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/flow_reductions.hpp"

namespace eulerfsi::kernels {

// The flow rate through the x-faces, taken in a pass that reads u anyway: the sum over the faces
// open to the flow of (1 - chi_u) u (kernels::open_face_sum's sum, in open_row_sum's order).
// Inactive: nothing summed, 0 returned.
struct OpenFaceSum {
  Mask2 chi_u;  // empty: every face open
  bool active = false;
};

// (1 - chi[k]) x[k] summed over [k0, k1) (chi null: x[k]), in kLanes partial sums added pairwise
// at the end: no chain of dependent additions, so the loop vectorises (the order is not a plain
// loop's: round-off).
KOKKOS_INLINE_FUNCTION double open_row_sum(const double* KOKKOS_RESTRICT x, const double* KOKKOS_RESTRICT chi, int k0,
                                           int k1) {
  constexpr int kLanes = 8;
  double lane[kLanes] = {};
  int k = k0;
  if (chi) {
    for (; k + kLanes <= k1; k += kLanes)
      for (int l = 0; l < kLanes; ++l) lane[l] += (1.0 - chi[k + l]) * x[k + l];
    for (int l = 0; k < k1; ++k, ++l) lane[l] += (1.0 - chi[k]) * x[k];
  } else {
    for (; k + kLanes <= k1; k += kLanes)
      for (int l = 0; l < kLanes; ++l) lane[l] += x[k + l];
    for (int l = 0; k < k1; ++k, ++l) lane[l] += x[k];
  }
  for (int width = kLanes / 2; width > 0; width /= 2)
    for (int l = 0; l < width; ++l) lane[l] += lane[l + width];
  return lane[0];
}

// out(i,j,k) = scale * [ (u(i)-u(i-1))/dx + (v(j)-v(j-1))/dy + (w(k)-w(k-1))/dz ]
// written at out(i - shift, j - shift, k - shift) for a cell (i, j, k); with the open faces' sum
// of u (OpenFaceSum) where a reduction asks for it.
template <class Out>
struct DivergenceAt {
  Out out;
  int shift;
  Field3 u, v, w;
  double ix, iy, iz;  // scale / h_D
  Mask2 chi_u;        // empty: every face open

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    out(i - shift, j - shift, k - shift) = (u(i, j, k) - u(i - 1, j, k)) * ix + (v(i, j, k) - v(i, j - 1, k)) * iy +
                                           (w(i, j, k) - w(i, j, k - 1)) * iz;
  }
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, double& sum) const {
    (*this)(i, j, k);
    sum += open_weight(chi_u, chi_u.extent(0) > 0, j, k) * u(i, j, k);
  }
  // host: the row (i, j) on raw pointers (k contiguous in every field), so the loop vectorises
  void row(int i, int j, int k0, int k1) const {
    double* KOKKOS_RESTRICT o = &out(i - shift, j - shift, k0 - shift) - k0;
    const double* KOKKOS_RESTRICT uc = &u(i, j, 0);
    const double* KOKKOS_RESTRICT um = &u(i - 1, j, 0);
    const double* KOKKOS_RESTRICT vc = &v(i, j, 0);
    const double* KOKKOS_RESTRICT vm = &v(i, j - 1, 0);
    const double* KOKKOS_RESTRICT wc = &w(i, j, 0);
    const double x = ix, y = iy, z = iz;
    EULERFSI_INDEPENDENT_LOOP
    for (int k = k0; k < k1; ++k) o[k] = (uc[k] - um[k]) * x + (vc[k] - vm[k]) * y + (wc[k] - wc[k - 1]) * z;
  }
  double row_reduce(int i, int j, int k0, int k1) const {
    row(i, j, k0, k1);
    return open_row_sum(&u(i, j, 0), chi_u.extent(0) > 0 ? &chi_u(j, 0) : nullptr, k0, k1);
  }
};

// The divergence of every cell of the box (DivergenceAt): shift = kGhost writes the interior as one
// contiguous block (a Poisson solver's own buffer, no copy in). Returns the open faces' sum of u
// when flow is active (0 otherwise).
template <class Out>
inline double divergence_shifted(const Out& out, int shift, const Field3& u, const Field3& v, const Field3& w,
                                 const double h[3], double scale, const Box& box, const OpenFaceSum& flow = {}) {
  const DivergenceAt<Out> div{out, shift, u, v, w, scale / h[0], scale / h[1], scale / h[2], flow.chi_u};
  if (!flow.active) {
    for_each_row("eulerfsi::projection::divergence", box, div);
    return 0.0;
  }
  double sum = 0.0;
  reduce_rows("eulerfsi::projection::divergence", box, div, Kokkos::Sum<double>(sum));
  return sum;
}

inline double divergence(const Field3& out, const Field3& u, const Field3& v, const Field3& w, const double h[3],
                         double scale, const Box& box, const OpenFaceSum& flow = {}) {
  return divergence_shifted(out, 0, u, v, w, h, scale, box, flow);
}

// The step's mean pressure: p_step = sum over substeps of alpha_s p_s (sum alpha_s = 1), so that
// the step's projections moved u by -dt grad p_step. first: the first substep starts the sum.
struct StepPressure {
  Field3 p_step;  // empty: not accumulated
  double alpha = 0.0;
  bool first = false;
};

// The constant flow rate's uniform correction, applied in the pressure correction's pass:
// u += du open_u(j, k) (du everywhere without a mask), as kernels::add_open_x_velocity does.
struct FlowRateShift {
  Mask2 open_u;
  double du = 0.0;
};

// The pressure correction of one cell (see subtract_gradient_impl below for the equations).
template <bool Accumulate>
struct GradientCorrection {
  Field3 u, v, w, phi, p_step;
  double ix, iy, iz;  // factor / h_D
  Mask2 open_u;       // empty: du on every face
  double du;
  double alpha;
  bool first;

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    const double p0 = phi(i, j, k);
    u(i, j, k) = (u(i, j, k) - (phi(i + 1, j, k) - p0) * ix) + (open_u.extent(0) > 0 ? du * open_u(j, k) : du);
    v(i, j, k) -= (phi(i, j + 1, k) - p0) * iy;
    w(i, j, k) -= (phi(i, j, k + 1) - p0) * iz;
    // a plain if: nvcc cannot first-capture a variable inside if constexpr in a device lambda
    if (Accumulate) p_step(i, j, k) = (first ? 0.0 : p_step(i, j, k)) + alpha * p0;
  }
  // host: the row (i, j) on raw pointers (k contiguous in every field), so the loop vectorises;
  // the same operations in the same order as the per-cell form
  void row(int i, int j, int k0, int k1) const {
    double* KOKKOS_RESTRICT ur = &u(i, j, 0);
    double* KOKKOS_RESTRICT vr = &v(i, j, 0);
    double* KOKKOS_RESTRICT wr = &w(i, j, 0);
    const double* KOKKOS_RESTRICT pc = &phi(i, j, 0);
    const double* KOKKOS_RESTRICT px = &phi(i + 1, j, 0);
    const double* KOKKOS_RESTRICT py = &phi(i, j + 1, 0);
    const double x = ix, y = iy, z = iz;
    if (open_u.extent(0) > 0) {
      const double* KOKKOS_RESTRICT o = &open_u(j, 0);
      const double d = du;
      EULERFSI_INDEPENDENT_LOOP
      for (int k = k0; k < k1; ++k) ur[k] = (ur[k] - (px[k] - pc[k]) * x) + d * o[k];
    } else {
      const double d = du;
      EULERFSI_INDEPENDENT_LOOP
      for (int k = k0; k < k1; ++k) ur[k] = (ur[k] - (px[k] - pc[k]) * x) + d;
    }
    EULERFSI_INDEPENDENT_LOOP
    for (int k = k0; k < k1; ++k) {
      vr[k] -= (py[k] - pc[k]) * y;
      wr[k] -= (pc[k + 1] - pc[k]) * z;
    }
    if constexpr (Accumulate) {
      double* KOKKOS_RESTRICT ps = &p_step(i, j, 0);
      const double a = alpha;
      if (first) {
        EULERFSI_INDEPENDENT_LOOP
        for (int k = k0; k < k1; ++k) ps[k] = 0.0 + a * pc[k];
      } else {
        EULERFSI_INDEPENDENT_LOOP
        for (int k = k0; k < k1; ++k) ps[k] = ps[k] + a * pc[k];
      }
    }
  }
};

// u_D(i) -= factor (phi(i + e_D) - phi(i)) / h_D for the three components in one sweep, then
// u += shift.du open_u(j, k), and p_step += alpha phi on the same cells (phi is read there anyway;
// p_step's ghosts are the caller's to fill). The shift does not change div u (it is uniform along
// x), and the corrected u's open-face sum is u*'s plus the shift's: sum_i (phi(i+1) - phi(i)) = 0
// on a periodic x line, so the flow rate taken from u* (divergence_shifted) is the corrected one's
// to round-off.
template <bool Accumulate>
inline void subtract_gradient_impl(const Field3& u, const Field3& v, const Field3& w, const Field3& phi,
                                   const double h[3], double factor, const StepPressure& step,
                                   const FlowRateShift& shift, const Box& box) {
  const GradientCorrection<Accumulate> correct{u, v, w, phi, step.p_step, factor / h[0], factor / h[1], factor / h[2],
                                               shift.open_u, shift.du, step.alpha, step.first};
  for_each_row("eulerfsi::projection::correct", box, correct);
}

inline void subtract_gradient(const Field3& u, const Field3& v, const Field3& w, const Field3& phi, const double h[3],
                              double factor, const Box& box, const StepPressure& step = {},
                              const FlowRateShift& shift = {}) {
  if (step.p_step.extent(0) > 0)
    subtract_gradient_impl<true>(u, v, w, phi, h, factor, step, shift, box);
  else
    subtract_gradient_impl<false>(u, v, w, phi, h, factor, step, shift, box);
}

}  // namespace eulerfsi::kernels
