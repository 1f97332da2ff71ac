#pragma once
// Transport of the solid volume fraction psi and of the left Cauchy-Green tensor B:
//   dpsi/dt = -div(u psi)
//   dB/dt   = -div(u B) + L B + B L^T,   L_ab = du_a/dx_b   (upper-convected derivative = 0)
// Advection in finite-difference flux form: F_{i+1/2} = u_{i+1/2} q^WENO5_{i+1/2}, upwinded by
// the sign of the face velocity; the rhs is the flux difference, so sum(psi) changes only
// through the boundary faces (conservative). Stretching with second-order central differences
// at the cell centre.
#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/momentum.hpp"
#include "kernels/offsets.hpp"
#include "kernels/solid_fields.hpp"
#include "kernels/weno5.hpp"

namespace eulerfsi::kernels {

// (F_D(i) - F_D(i - e_D)) / h_D with F_D(i) = u_D(i) q^WENO at the face between i and i+e_D.
template <int D, class Q>
KOKKOS_FORCEINLINE_FUNCTION double weno_flux_difference(const Q& q, const Field3& uD, double inv_h, int i, int j,
                                                        int k) {
  const double up = uD(i, j, k);
  const double um = shifted<D>(uD, i, j, k, -1);
  const double fp = up * face_value_upwind<D>(q, up, i, j, k);
  const double fm = um * face_value_upwind<D>(q, um, i - Unit<D>::i, j - Unit<D>::j, k - Unit<D>::k);
  return (fp - fm) * inv_h;
}

template <class Q>
KOKKOS_FORCEINLINE_FUNCTION double weno_divergence(const Q& q, const Field3& u, const Field3& v, const Field3& w,
                                                   const double inv_h[3], int i, int j, int k) {
  return weno_flux_difference<0>(q, u, inv_h[0], i, j, k) + weno_flux_difference<1>(q, v, inv_h[1], i, j, k) +
         weno_flux_difference<2>(q, w, inv_h[2], i, j, k);
}

// L_AB = du_A/dx_B at the centre of cell (i,j,k): the diagonal from the cell's two A-faces,
// off-diagonals as central differences of the two-face averages (four faces around the centre).
template <int A, int B>
KOKKOS_FORCEINLINE_FUNCTION double velocity_gradient_at_centre(const Field3& uA, const double inv_h[3], int i, int j,
                                                               int k) {
  if constexpr (A == B) {
    return (uA(i, j, k) - shifted<A>(uA, i, j, k, -1)) * inv_h[A];
  } else {
    return 0.25 * inv_h[B] *
           (shifted<B>(uA, i, j, k, 1) + shifted<A, B>(uA, i, j, k, -1, 1) - shifted<B>(uA, i, j, k, -1) -
            shifted<A, B>(uA, i, j, k, -1, -1));
  }
}

// Largest |psi| on the 19-point star of radius 3 that the face fluxes of cell (i,j,k) read: zero
// means every flux through the cell's faces is exactly zero (|psi|, so that an undershoot below
// zero still counts: skipping it on one side of a face only would break conservation).
template <class Q>
KOKKOS_FORCEINLINE_FUNCTION double star_max(const Q& psi, int i, int j, int k) {
  double m = compat::fabs(psi(i, j, k));
  for (int r = 1; r <= 3; ++r) {
    m = compat::fmax(m, compat::fmax(compat::fabs(psi(i - r, j, k)), compat::fabs(psi(i + r, j, k))));
    m = compat::fmax(m, compat::fmax(compat::fabs(psi(i, j - r, k)), compat::fabs(psi(i, j + r, k))));
    m = compat::fmax(m, compat::fmax(compat::fabs(psi(i, j, k - r)), compat::fabs(psi(i, j, k + r))));
  }
  return m;
}

// rhs = -div_h^WENO(u psi); exactly 0 where the star holds no psi (the paper model's box path
// relies on it: its rhs box is psi's support grown by the star's radius, src/solid/paper_model.cpp).
inline void scalar_advection_rhs(const WindowField& rhs, const WindowField& q, const Velocity& vel, const double h[3],
                                 const Box& box) {
  const double ih0 = 1.0 / h[0], ih1 = 1.0 / h[1], ih2 = 1.0 / h[2];
  const Field3 u = vel.c[0], v = vel.c[1], w = vel.c[2];
  for_each_cell("eulerfsi::solid::psi_rhs", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double inv_h[3] = {ih0, ih1, ih2};
    // the fluid far from every body: nothing to transport
    rhs(i, j, k) = star_max(q, i, j, k) == 0.0 ? 0.0 : -weno_divergence(q, u, v, w, inv_h, i, j, k);
  });
}

// rhs_ab = -div_h^WENO(u B_ab) + (L B + B L^T)_ab for all six components in one pass (u, v, w
// and the nine gradients are read once per cell). Far from the body (psi < psi_min on the whole
// stencil) B = I was reset and stays I: the rhs is zero there, which also skips most cells.
struct TensorTransportRhs {
  Tensor6 rhs, b;
  Field3 u, v, w;
  WindowField psi;
  double psi_min;
  double inv_h[3];

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (star_max(psi, i, j, k) < psi_min) {
      for (int s = 0; s < kTensorComponents; ++s) rhs.c[s](i, j, k) = 0.0;
      return;
    }
    double L[3][3];
    L[0][0] = velocity_gradient_at_centre<0, 0>(u, inv_h, i, j, k);
    L[0][1] = velocity_gradient_at_centre<0, 1>(u, inv_h, i, j, k);
    L[0][2] = velocity_gradient_at_centre<0, 2>(u, inv_h, i, j, k);
    L[1][0] = velocity_gradient_at_centre<1, 0>(v, inv_h, i, j, k);
    L[1][1] = velocity_gradient_at_centre<1, 1>(v, inv_h, i, j, k);
    L[1][2] = velocity_gradient_at_centre<1, 2>(v, inv_h, i, j, k);
    L[2][0] = velocity_gradient_at_centre<2, 0>(w, inv_h, i, j, k);
    L[2][1] = velocity_gradient_at_centre<2, 1>(w, inv_h, i, j, k);
    L[2][2] = velocity_gradient_at_centre<2, 2>(w, inv_h, i, j, k);
    double B[3][3];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) B[a][c] = b.c[tensor_index(a, c)](i, j, k);
    // component (a, c) of each of the six storage slots
    const int ra[kTensorComponents] = {0, 1, 2, 0, 0, 1};
    const int rc[kTensorComponents] = {0, 1, 2, 1, 2, 2};
    for (int s = 0; s < kTensorComponents; ++s) {
      const int a = ra[s], c = rc[s];
      double stretch = 0.0;
      for (int m = 0; m < 3; ++m) stretch += L[a][m] * B[m][c] + B[a][m] * L[c][m];
      rhs.c[s](i, j, k) = stretch - weno_divergence(b.c[s], u, v, w, inv_h, i, j, k);
    }
  }
};

// psi_min: the volume fraction below which B is reset to I (a negative value computes every cell).
inline void tensor_transport_rhs(const Tensor6& rhs, const Tensor6& b, const Velocity& vel, const WindowField& psi,
                                 double psi_min, const double h[3], const Box& box) {
  TensorTransportRhs f{rhs, b, vel.c[0], vel.c[1], vel.c[2], psi, psi_min, {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]}};
  for_each_cell("eulerfsi::solid::b_rhs", box, f);
}

// Low-storage RK3 substep: q += dt (gamma rhs + zeta rhs_old). The caller swaps rhs and rhs_old.
// q = q0 + dt (gamma rhs + zeta rhs_old) on one field (q may be q0); flat indices on the shared
// layout, so the k loop vectorises: the four fields lie on one window (one body's, or the slab).
inline void rk3_field_update(const WindowField& q, const WindowField& q0, const WindowField& rhs,
                             const WindowField& rhs_old, double a, double c, const Box& box, const char* label) {
  const long s0 = long(q.data.stride(0)), s1 = long(q.data.stride(1));
  const int l0 = q.lo[0], l1 = q.lo[1], l2 = q.lo[2];
  double* out = q.data.data();
  const double *in = q0.data.data(), *r = rhs.data.data(), *ro = rhs_old.data.data();
  for_each_cell(label, box, KOKKOS_LAMBDA(int i, int j, int k) {
    const long n = (i - l0) * s0 + (j - l1) * s1 + (k - l2);
    out[n] = in[n] + a * r[n] + c * ro[n];
  });
}

inline void rk3_scalar_update(const WindowField& q, const WindowField& rhs, const WindowField& rhs_old, double dt,
                              double gamma, double zeta, const Box& box) {
  rk3_field_update(q, q, rhs, rhs_old, dt * gamma, dt * zeta, box, "eulerfsi::solid::psi_update");
}

// B = B0 + dt (gamma rhs + zeta rhs_old), component by component (B0: the tensor before the
// substep, kept by the caller as B_prev); every tensor on one window.
inline void rk3_tensor_update(const Tensor6& b, const Tensor6& b0, const Tensor6& rhs, const Tensor6& rhs_old, double dt,
                              double gamma, double zeta, const Box& box) {
  for (int s = 0; s < kTensorComponents; ++s)
    rk3_field_update(b.c[s], b0.c[s], rhs.c[s], rhs_old.c[s], dt * gamma, dt * zeta, box, "eulerfsi::solid::b_update");
}

namespace detail {
// The seven fields' data of rk3_body_update (at namespace scope: nvcc refuses a function-local
// type in a device lambda's capture).
struct BodyUpdatePointers {
  static constexpr int kFields = kTensorComponents + 1;
  double* out[kFields];
  const double *in[kFields], *r[kFields], *ro[kFields];
};
}  // namespace detail

// psi and B's six components in one pass (one launch instead of seven; the same arithmetic as
// rk3_scalar_update and rk3_tensor_update), B0 the tensor before the substep; every field on one
// window.
inline void rk3_body_update(const WindowField& psi, const WindowField& psi_rhs, const WindowField& psi_rhs_old,
                            const Tensor6& b, const Tensor6& b0, const Tensor6& rhs, const Tensor6& rhs_old, double dt,
                            double gamma, double zeta, const Box& box) {
  constexpr int kFields = detail::BodyUpdatePointers::kFields;
  detail::BodyUpdatePointers p;
  for (int s = 0; s < kFields; ++s) {
    const bool scalar = s == kTensorComponents;
    p.out[s] = scalar ? psi.data.data() : b.c[s].data.data();
    p.in[s] = scalar ? psi.data.data() : b0.c[s].data.data();
    p.r[s] = scalar ? psi_rhs.data.data() : rhs.c[s].data.data();
    p.ro[s] = scalar ? psi_rhs_old.data.data() : rhs_old.c[s].data.data();
  }
  const double a = dt * gamma, c = dt * zeta;
  const long s0 = long(psi.data.stride(0)), s1 = long(psi.data.stride(1));
  const int l0 = psi.lo[0], l1 = psi.lo[1], l2 = psi.lo[2];
  for_each_cell("eulerfsi::solid::body_update", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const long n = (i - l0) * s0 + (j - l1) * s1 + (k - l2);
    for (int s = 0; s < kFields; ++s) p.out[s][n] = p.in[s][n] + a * p.r[s][n] + c * p.ro[s][n];
  });
}

// psi = min(max(psi, 0), 1): WENO5 is essentially non-oscillatory, not bounded, so a sharp
// interface leaves over- and undershoots of a few 1e-3 that clipping removes. Returns the local
// volume removed, sum (psi_before - psi_after), for the conservative correction below.
inline double clip_volume_fraction(const Field3& psi, const Box& box) {
  double removed = 0.0;
  reduce_cells("eulerfsi::solid::psi_clip", box, KOKKOS_LAMBDA(int i, int j, int k, double& r) {
    const double before = psi(i, j, k);
    const double after = compat::fmin(compat::fmax(before, 0.0), 1.0);
    psi(i, j, k) = after;
    r += before - after;
  }, Kokkos::Sum<double>(removed));
  return removed;
}

// sum psi (1 - psi): the weight of the interface cells that take back the clipped volume.
inline double interface_weight(const Field3& psi, const Box& box) {
  double w = 0.0;
  reduce_cells("eulerfsi::solid::psi_interface", box, KOKKOS_LAMBDA(int i, int j, int k, double& r) {
    const double p = psi(i, j, k);
    r += p * (1.0 - p);
  }, Kokkos::Sum<double>(w));
  return w;
}

// psi += c psi (1 - psi): returns the clipped volume to the interface only, and keeps psi in
// [0, 1] while |c| <= 1 (the clipped volume is a tiny fraction of the interface weight).
inline void add_to_interface(const WindowField& psi, double c, const Box& box) {
  for_each_cell("eulerfsi::solid::psi_restore", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double p = psi(i, j, k);
    psi(i, j, k) = p + c * p * (1.0 - p);
  });
}

// The clip with a floor, psi = 0 where psi < floor (negative values included), min(psi, 1)
// elsewhere, and both sums above, the removed volume sum (psi_before - psi_after) and the weight
// sum psi (1 - psi) after the clip, in an order fixed by the cells alone: each row (i, j) summed
// along k into `rows`, then the rows in order of i and j on the host. A zero term (a cell without
// psi) leaves such a running sum's bits unchanged wherever it falls, so every box that holds
// psi's support gives the same two sums, on any number of threads: the paper model's box path
// equals its whole-slab path bit for bit (a Kokkos reduction splits its terms among threads by
// the box's shape, which changes the rounding). rows: at least 2 x (box's i-extent x j-extent).
struct ClipSums {
  double removed = 0.0, weight = 0.0;
};
using RowSums = Kokkos::View<double*, Kokkos::LayoutRight, MemSpace>;

inline ClipSums clip_volume_fraction_ordered(const WindowField& psi, const RowSums& rows, double psi_floor, const Box& box) {
  ClipSums sums;
  if (box.empty()) return sums;
  const int i0 = box.lo[0], j0 = box.lo[1], k0 = box.lo[2], k1 = box.hi[2];
  const int nj = box.hi[1] - box.lo[1];
  const long n = 2L * (box.hi[0] - box.lo[0]) * nj;
  Kokkos::parallel_for("eulerfsi::solid::psi_clip_rows", plane_policy(box), KOKKOS_LAMBDA(int i, int j) {
    double removed = 0.0, weight = 0.0;
    for (int k = k0; k < k1; ++k) {
      const double before = psi(i, j, k);
      const double after = before < psi_floor ? 0.0 : compat::fmin(before, 1.0);
      psi(i, j, k) = after;
      removed += before - after;
      weight += after * (1.0 - after);
    }
    const long r = 2L * ((i - i0) * long(nj) + (j - j0));
    rows(r) = removed;
    rows(r + 1) = weight;
  });
  const auto host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(),
                                                        Kokkos::subview(rows, Kokkos::make_pair(0L, n)));
  for (long r = 0; r < n; r += 2) {
    sums.removed += host(r);
    sums.weight += host(r + 1);
  }
  return sums;
}

// B = F F^T is symmetric positive definite. WENO reconstructs each component on its own and can
// overshoot where B jumps (the edge of the solid), leaving a B with a negative eigenvalue: a
// material of negative stiffness whose stress makes the coupled system blow up. Sylvester's
// criterion (all leading principal minors > 0) finds such cells (kernels/tensor_extension.hpp
// then replaces them by the mean of their neighbours).
KOKKOS_INLINE_FUNCTION bool positive_definite(double xx, double yy, double zz, double xy, double xz, double yz) {
  const double m2 = xx * yy - xy * xy;
  const double det = xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
  return xx > 0.0 && m2 > 0.0 && det > 0.0;
}

}  // namespace eulerfsi::kernels
