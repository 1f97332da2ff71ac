#pragma once
// Elastic stress of one soft body and the mixture viscosity:
//   rhs_D += d/dx_E S_DE,   S = psi G ((B^k + B^(k-1))/2 - I)   at cell centres
// on the MAC grid with the stencil of the viscous term in kernels/momentum.hpp: S_DD is
// differenced between the two cells of the D-face, S_DE (E != D) is averaged from the four
// cells around each edge and differenced across the face. The shear stresses are computed once per
// cell into a scratch (shear_stress), the normal ones where the face reads them.
#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/momentum.hpp"
#include "kernels/offsets.hpp"
#include "kernels/predictor_terms.hpp"
#include "kernels/solid_fields.hpp"

namespace eulerfsi::kernels {

// S_AB at cell (i,j,k) with the Crank-Nicolson average of B (explicit: B is advanced first).
template <int A, int B>
KOKKOS_FORCEINLINE_FUNCTION double elastic_stress(const WindowField& psi, const Tensor6& b, const Tensor6& bp, double G,
                                                  int i, int j, int k) {
  constexpr int s = A == B ? A : (A + B == 1 ? XY : (A + B == 2 ? XZ : YZ));
  return psi(i, j, k) * G * (0.5 * (b.c[s](i, j, k) + bp.c[s](i, j, k)) - (A == B ? 1.0 : 0.0));
}

// The shear stresses S_xy, S_xz, S_yz at the cell centres of `box`, into shear.c[0..2]: each face
// reads eight of them (two edges of four cells) per E, so they are computed once per cell.
inline void shear_stress(const Scratch3& shear, const WindowField& psi, const Tensor6& b, const Tensor6& bp, double G,
                         const Box& box) {
  const Scratch3 s = shear;
  const Tensor6 bb = b, bbp = bp;
  for_each_cell("eulerfsi::solid::shear_stress", box, KOKKOS_LAMBDA(int i, int j, int k) {
    s.c[0](i, j, k) = elastic_stress<0, 1>(psi, bb, bbp, G, i, j, k);
    s.c[1](i, j, k) = elastic_stress<0, 2>(psi, bb, bbp, G, i, j, k);
    s.c[2](i, j, k) = elastic_stress<1, 2>(psi, bb, bbp, G, i, j, k);
  });
}

// Where the face kernels take S_DE (D != E) from: shear_stress()'s scratch in the step, B itself in
// the diagnostics (which run between steps, when the scratch holds nothing).
struct ShearFromScratch {
  Scratch3 s;
  template <int D, int E>
  KOKKOS_FORCEINLINE_FUNCTION double at(int i, int j, int k) const {
    static_assert(D != E, "S_DD is not stored");
    return s.c[D + E - 1](i, j, k);  // xy: 0, xz: 1, yz: 2
  }
};
struct ShearFromB {
  WindowField psi;
  Tensor6 b, bp;
  double G;
  template <int D, int E>
  KOKKOS_FORCEINLINE_FUNCTION double at(int i, int j, int k) const {
    return elastic_stress<D, E>(psi, b, bp, G, i, j, k);
  }
};

// S_DE at the edge (i + e_D/2 + e_E/2): average of its four cells.
template <int D, int E, class Shear>
KOKKOS_FORCEINLINE_FUNCTION double elastic_stress_edge(const Shear& s, int i, int j, int k) {
  constexpr int di = Unit<D>::i, dj = Unit<D>::j, dk = Unit<D>::k;
  constexpr int ei = Unit<E>::i, ej = Unit<E>::j, ek = Unit<E>::k;
  return 0.25 * (s.template at<D, E>(i, j, k) + s.template at<D, E>(i + di, j + dj, k + dk) +
                 s.template at<D, E>(i + ei, j + ej, k + ek) + s.template at<D, E>(i + di + ei, j + dj + ej, k + dk + ek));
}

// (div S)_D at the D-face between cells i and i + e_D; S_DE (E != D) from `shear`.
template <int D, class Shear>
KOKKOS_FORCEINLINE_FUNCTION double elastic_force_at_face(const WindowField& psi, const Tensor6& b, const Tensor6& bp,
                                                         const Shear& shear, double G, const double inv_h[3], int i,
                                                         int j, int k) {
  constexpr int E1 = (D + 1) % 3, E2 = (D + 2) % 3;
  const double fn = (elastic_stress<D, D>(psi, b, bp, G, i + Unit<D>::i, j + Unit<D>::j, k + Unit<D>::k) -
                     elastic_stress<D, D>(psi, b, bp, G, i, j, k)) *
                    inv_h[D];
  const double f1 = (elastic_stress_edge<D, E1>(shear, i, j, k) -
                     elastic_stress_edge<D, E1>(shear, i - Unit<E1>::i, j - Unit<E1>::j, k - Unit<E1>::k)) *
                    inv_h[E1];
  const double f2 = (elastic_stress_edge<D, E2>(shear, i, j, k) -
                     elastic_stress_edge<D, E2>(shear, i - Unit<E2>::i, j - Unit<E2>::j, k - Unit<E2>::k)) *
                    inv_h[E2];
  return fn + f1 + f2;
}

// Largest psi over the ten cells the D-face stencil reads: the two cells of the face and their
// neighbours across each edge. Zero means a zero force (most faces, far from the body).
template <int D>
KOKKOS_FORCEINLINE_FUNCTION double face_stencil_max(const WindowField& psi, int i, int j, int k) {
  constexpr int E1 = (D + 1) % 3, E2 = (D + 2) % 3;
  double m = 0.0;
  for (int a = 0; a <= 1; ++a) {
    m = compat::fmax(m, shifted<D>(psi, i, j, k, a));
    for (int s = -1; s <= 1; s += 2) {
      m = compat::fmax(m, shifted<D, E1>(psi, i, j, k, a, s));
      m = compat::fmax(m, shifted<D, E2>(psi, i, j, k, a, s));
    }
  }
  return m;
}

template <int D>
struct ElasticForce {
  Field3 rhs;
  WindowField psi;
  Tensor6 b, bp;
  ShearFromScratch shear;
  double G;
  double inv_h[3];
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (face_stencil_max<D>(psi, i, j, k) == 0.0) return;
    rhs(i, j, k) += elastic_force_at_face<D>(psi, b, bp, shear, G, inv_h, i, j, k);
  }
};

// The cells the D-face stencils of `faces` read (each face: its two cells and their neighbours
// across each edge), within `limit` (the body's window).
inline Box stress_cells(const Box& faces, const Box& limit) { return faces.grown(1, limit); }

// rhs_D += (div S)_D on the D-faces of `box` for D = x, y, z (one body; call once per body);
// `shear`: scratch on psi's window.
inline void add_elastic_force(const Velocity& rhs, const WindowField& psi, const Tensor6& b, const Tensor6& b_prev,
                              const Scratch3& shear, double G, const double h[3], const Box& box) {
  if (box.empty()) return;
  shear_stress(shear, psi, b, b_prev, G, stress_cells(box, psi.window()));
  const double ih0 = 1.0 / h[0], ih1 = 1.0 / h[1], ih2 = 1.0 / h[2];
  for_each_cell("eulerfsi::solid::elastic_u", box,
                ElasticForce<0>{rhs.c[0], psi, b, b_prev, {shear}, G, {ih0, ih1, ih2}});
  for_each_cell("eulerfsi::solid::elastic_v", box,
                ElasticForce<1>{rhs.c[1], psi, b, b_prev, {shear}, G, {ih0, ih1, ih2}});
  for_each_cell("eulerfsi::solid::elastic_w", box,
                ElasticForce<2>{rhs.c[2], psi, b, b_prev, {shear}, G, {ih0, ih1, ih2}});
}

// The same force added after the constant-viscosity predictor has run over the whole grid
// without it (kernels/momentum_predictor.hpp), where u* is linear in rhs^k:
//   rhs^k_D += f_D,   u*_D += dt gamma f_D / (1 + pen_D)
// (equal to predicting with rhs^k + f to round-off). One pass over the body's faces instead of
// splitting the grid's predictor into the boxes around them.
template <int D>
struct ElasticForceOnPredictor {
  Field3 rhs, star;
  WindowField psi;
  Tensor6 b, bp;
  ShearFromScratch shear;
  double G;
  double inv_h[3];
  PredictorTerms terms;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (face_stencil_max<D>(psi, i, j, k) == 0.0) return;
    const double f = elastic_force_at_face<D>(psi, b, bp, shear, G, inv_h, i, j, k);
    rhs(i, j, k) += f;
    star(i, j, k) += terms.a * f / (1.0 + terms.penal * terms.chi_row(D, j)[k]);
  }
};

// rhs^k and u* (the predictor's output) on the faces of `box`, one body; `shear`: scratch on psi's window.
inline void add_elastic_force_to_predictor(const Velocity& rhs, const Velocity& star, const PredictorTerms& terms,
                                           const WindowField& psi, const Tensor6& b, const Tensor6& b_prev,
                                           const Scratch3& shear, double G, const double h[3], const Box& box) {
  if (box.empty()) return;
  shear_stress(shear, psi, b, b_prev, G, stress_cells(box, psi.window()));
  const double ih0 = 1.0 / h[0], ih1 = 1.0 / h[1], ih2 = 1.0 / h[2];
  for_each_cell("eulerfsi::solid::elastic_u_star", box,
                ElasticForceOnPredictor<0>{rhs.c[0], star.c[0], psi, b, b_prev, {shear}, G, {ih0, ih1, ih2}, terms});
  for_each_cell("eulerfsi::solid::elastic_v_star", box,
                ElasticForceOnPredictor<1>{rhs.c[1], star.c[1], psi, b, b_prev, {shear}, G, {ih0, ih1, ih2}, terms});
  for_each_cell("eulerfsi::solid::elastic_w_star", box,
                ElasticForceOnPredictor<2>{rhs.c[2], star.c[2], psi, b, b_prev, {shear}, G, {ih0, ih1, ih2}, terms});
}

// f = value on `box` (a Box, unlike Kokkos::deep_copy on a whole View).
inline void fill_box(const Field3& f, double value, const Box& box) {
  for_each_cell("eulerfsi::fill_box", box, KOKKOS_LAMBDA(int i, int j, int k) { f(i, j, k) = value; });
}

// mu += psi dmu: the caller starts from mu = mu_f and adds each body with dmu = mu_s - mu_f,
// giving mu = (1 - sum psi) mu_f + sum psi mu_s.
inline void mixture_viscosity_add(const Field3& mu, const WindowField& psi, double dmu, const Box& box) {
  for_each_cell("eulerfsi::solid::mixture_viscosity", box, KOKKOS_LAMBDA(int i, int j, int k) {
    mu(i, j, k) += psi(i, j, k) * dmu;
  });
}

// The neo-Hookean elastic energy per unit volume, out += psi G (tr B / det(B)^(1/3) - 3) / 2: the
// isochoric form, zero for B = I and never negative (the arithmetic-geometric mean of B's
// eigenvalues), also where the discrete B is not exactly volume-preserving (det B = 1 is exact
// only in the continuum). The field snapshots' measure of how strained the solid is.
inline void elastic_energy_add(const Field3& out, const WindowField& psi, const Tensor6& b, double G, const Box& box) {
  const Tensor6 t = b;
  for_each_cell("eulerfsi::solid::elastic_energy", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double xx = t.c[XX](i, j, k), yy = t.c[YY](i, j, k), zz = t.c[ZZ](i, j, k);
    const double xy = t.c[XY](i, j, k), xz = t.c[XZ](i, j, k), yz = t.c[YZ](i, j, k);
    const double det = xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
    if (det <= 0.0) return;  // not a deformation (never for B = F F^T); leaves the cell at 0
    out(i, j, k) += psi(i, j, k) * 0.5 * G * ((xx + yy + zz) * compat::pow(det, -1.0 / 3.0) - 3.0);
  });
}

}  // namespace eulerfsi::kernels
