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
// P: a window field or the row kernels' RowCells, T: a Tensor6 or RowTensor.
template <int A, int B, class P, class T>
KOKKOS_FORCEINLINE_FUNCTION double elastic_stress(const P& psi, const T& b, const T& bp, double G, int i, int j, int k) {
  constexpr int s = A == B ? A : (A + B == 1 ? XY : (A + B == 2 ? XZ : YZ));
  return psi(i, j, k) * G * (0.5 * (b.c[s](i, j, k) + bp.c[s](i, j, k)) - (A == B ? 1.0 : 0.0));
}

// One row's 3 x 3 neighbourhood of rows (i0 + di, j0 + dj; di, dj in -1..1) of a window field as raw
// pointers from k0 on: the row kernels index it without the window's offsets on every access, so
// the k loop vectorises. The stencil functions take it in place of the field (the same values).
struct RowCells {
  const double* row[3][3] = {};
  int i0 = 0, j0 = 0, k0 = 0;
  RowCells() = default;
  KOKKOS_INLINE_FUNCTION RowCells(const WindowField& f, int i, int j, int k) : i0(i), j0(j), k0(k) {
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) row[a][c] = &f(i + a - 1, j + c - 1, k);
  }
  KOKKOS_FORCEINLINE_FUNCTION double operator()(int i, int j, int k) const { return row[i - i0 + 1][j - j0 + 1][k - k0]; }
};
struct RowTensor {
  RowCells c[kTensorComponents];
};

// S_xy, S_xz, S_yz at the cell centres of one row (k0..k1) into shear.c[0..2].
struct ShearStressRow {
  Scratch3 shear;
  WindowField psi;
  Tensor6 b, bp;
  double G;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {  // GPUs: per cell
    shear.c[0](i, j, k) = elastic_stress<0, 1>(psi, b, bp, G, i, j, k);
    shear.c[1](i, j, k) = elastic_stress<0, 2>(psi, b, bp, G, i, j, k);
    shear.c[2](i, j, k) = elastic_stress<1, 2>(psi, b, bp, G, i, j, k);
  }
  void row(int i, int j, int k0, int k1) const {
    const double* ps = &psi(i, j, k0);
    const double* bs[3] = {&b.c[XY](i, j, k0), &b.c[XZ](i, j, k0), &b.c[YZ](i, j, k0)};
    const double* bps[3] = {&bp.c[XY](i, j, k0), &bp.c[XZ](i, j, k0), &bp.c[YZ](i, j, k0)};
    for (int c = 0; c < 3; ++c) {
      double* out = &shear.c[c](i, j, k0);
      EULERFSI_INDEPENDENT_LOOP
      for (int n = 0; n < k1 - k0; ++n)  // elastic_stress<D, E>'s expression (its "- 0" too: the same bits)
        out[n] = ps[n] * G * (0.5 * (bs[c][n] + bps[c][n]) - 0.0);
    }
  }
};

// The shear stresses S_xy, S_xz, S_yz at the cell centres of `box`, into shear.c[0..2]: each face
// reads eight of them (two edges of four cells) per E, so they are computed once per cell.
inline void shear_stress(const Scratch3& shear, const WindowField& psi, const Tensor6& b, const Tensor6& bp, double G,
                         const Box& box) {
  for_each_row("eulerfsi::solid::shear_stress", box, ShearStressRow{shear, psi, b, bp, G});
}

// Where the face kernels take S_DE (D != E) from: shear_stress()'s scratch in the step, B itself in
// the diagnostics (which run between steps, when the scratch holds nothing).
template <class S>
struct ShearFrom {
  S s[3];  // S_xy, S_xz, S_yz: window fields, or RowCells in the row kernels
  template <int D, int E>
  KOKKOS_FORCEINLINE_FUNCTION double at(int i, int j, int k) const {
    static_assert(D != E, "S_DD is not stored");
    return s[D + E - 1](i, j, k);  // xy: 0, xz: 1, yz: 2
  }
};
using ShearFromScratch = ShearFrom<WindowField>;
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
template <int D, class P, class T, class Shear>
KOKKOS_FORCEINLINE_FUNCTION double elastic_force_at_face(const P& psi, const T& b, const T& bp, const Shear& shear,
                                                         double G, const double inv_h[3], int i, int j, int k) {
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
template <int D, class P>
KOKKOS_FORCEINLINE_FUNCTION double face_stencil_max(const P& psi, int i, int j, int k) {
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

// The row kernels' view of a body's fields around row (i, j): psi, B_DD and B_prev_DD, the shear
// stresses (RowCells; the other tensor components are not read by the D-face stencil).
template <int D>
struct FaceRow {
  RowCells psi;
  RowTensor b, bp;
  ShearFrom<RowCells> shear;
  KOKKOS_INLINE_FUNCTION FaceRow(const WindowField& p, const Tensor6& bt, const Tensor6& bpt, const ShearFromScratch& s,
                                 int i, int j, int k0)
      : psi(p, i, j, k0) {
    b.c[D] = RowCells(bt.c[D], i, j, k0);
    bp.c[D] = RowCells(bpt.c[D], i, j, k0);
    for (int c = 0; c < 3; ++c) shear.s[c] = RowCells(s.s[c], i, j, k0);
  }
};

inline ShearFromScratch shear_from(const Scratch3& s) { return ShearFromScratch{{s.c[0], s.c[1], s.c[2]}}; }

// rhs_D += (div S)_D on the D-faces, D = x, y, z in one pass (the three read the same psi and shear
// stresses, once from memory). OnPredictor: the force is added after the constant-viscosity
// predictor has run over the whole grid without it (kernels/momentum_predictor.hpp), where u* is
// linear in rhs^k:
//   rhs^k_D += f_D,   u*_D += dt gamma f_D / (1 + pen_D)
// (equal to predicting with rhs^k + f to round-off): one pass over the body's faces instead of
// splitting the grid's predictor into the boxes around them.
template <bool OnPredictor>
struct ElasticForces {
  Velocity rhs, star;  // star: u* (OnPredictor only)
  WindowField psi;
  Tensor6 b, bp;
  ShearFromScratch shear;
  double G;
  double inv_h[3];
  PredictorTerms terms;  // OnPredictor only

  template <int D>
  KOKKOS_FORCEINLINE_FUNCTION void face(int i, int j, int k) const {
    if (face_stencil_max<D>(psi, i, j, k) == 0.0) return;  // no psi in the stencil: no force
    const double f = elastic_force_at_face<D>(psi, b, bp, shear, G, inv_h, i, j, k);
    rhs.c[D](i, j, k) += f;
    if (OnPredictor) star.c[D](i, j, k) += terms.a * f / (1.0 + terms.penal * terms.chi_row(D, j)[k]);
  }
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {  // GPUs: per cell, its three faces
    face<0>(i, j, k);
    face<1>(i, j, k);
    face<2>(i, j, k);
  }

  // The D-faces of a row: the force is computed on every face and kept where the stencil holds psi
  // (a select, so the loop vectorises; the other faces keep rhs and u* as face() leaves them).
  template <int D>
  void row_of(int i, int j, int k0, int k1) const {
    const FaceRow<D> f(psi, b, bp, shear, i, j, k0);
    double* r = &rhs.c[D](i, j, k0);
    double* u = OnPredictor ? &star.c[D](i, j, k0) : nullptr;
    const double* chi = OnPredictor ? terms.chi_row(D, j) : nullptr;
    EULERFSI_INDEPENDENT_LOOP
    for (int k = k0; k < k1; ++k) {
      const double m = face_stencil_max<D>(f.psi, i, j, k);
      const double force = elastic_force_at_face<D>(f.psi, f.b, f.bp, f.shear, G, inv_h, i, j, k);
      r[k - k0] = m == 0.0 ? r[k - k0] : r[k - k0] + force;
      if (OnPredictor) u[k - k0] = m == 0.0 ? u[k - k0] : u[k - k0] + terms.a * force / (1.0 + terms.penal * chi[k]);
    }
  }
  void row(int i, int j, int k0, int k1) const {  // hosts: the row's data stays in cache for all three
    row_of<0>(i, j, k0, k1);
    row_of<1>(i, j, k0, k1);
    row_of<2>(i, j, k0, k1);
  }
};

// The cells the D-face stencils of `faces` read (each face: its two cells and their neighbours
// across each edge), within `limit` (the body's window).
inline Box stress_cells(const Box& faces, const Box& limit) { return faces.grown(1, limit); }

// The shear stresses on the cells the faces read, then the faces' force: f's fields are one body's.
template <bool OnPredictor>
void launch_elastic_forces(const ElasticForces<OnPredictor>& f, const Scratch3& shear, const Box& box, const char* label) {
  if (box.empty()) return;
  shear_stress(shear, f.psi, f.b, f.bp, f.G, stress_cells(box, f.psi.window()));
  for_each_row(label, box, f);
}

// rhs_D += (div S)_D on the D-faces of `box` for D = x, y, z (one body; call once per body);
// `shear`: scratch on psi's window.
inline void add_elastic_force(const Velocity& rhs, const WindowField& psi, const Tensor6& b, const Tensor6& b_prev,
                              const Scratch3& shear, double G, const double h[3], const Box& box) {
  const ElasticForces<false> f{rhs, Velocity{}, psi, b, b_prev, shear_from(shear), G, {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]}, {}};
  launch_elastic_forces(f, shear, box, "eulerfsi::solid::elastic_force");
}

// rhs^k and u* (`star`, the predictor's output) on the faces of `box`, one body; `shear`: scratch
// on psi's window.
inline void add_elastic_force_to_predictor(const Velocity& rhs, const Velocity& star, const PredictorTerms& terms,
                                           const WindowField& psi, const Tensor6& b, const Tensor6& b_prev,
                                           const Scratch3& shear, double G, const double h[3], const Box& box) {
  const ElasticForces<true> f{rhs, star, psi, b, b_prev, shear_from(shear), G, {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]},
                              terms};
  launch_elastic_forces(f, shear, box, "eulerfsi::solid::elastic_force_on_predictor");
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
